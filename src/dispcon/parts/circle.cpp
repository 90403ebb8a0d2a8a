#include "dispcon/parts/circle.hpp"

namespace dispcon {

Nearest nearest_on_circle(const Vec3& p1, const Vec3& n, double radius, const Vec3& p) {
  Nearest out;
  const Vec3 d = p - p1;
  const Vec3 e = unit_or(d - d.dot(n) * n, any_perpendicular(n));
  out.q = p1 + radius * e;
  out.rows = 2;
  out.normals[0] = n;
  out.normals[1] = e;
  return out;
}

}  // namespace dispcon
