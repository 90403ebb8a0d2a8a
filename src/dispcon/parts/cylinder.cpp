#include "dispcon/parts/cylinder.hpp"

#include <algorithm>

namespace dispcon {

Nearest nearest_on_cylinder(const Vec3& p1, const Vec3& u, double radius, double l1, double l2,
                            const Vec3& p, BoundTest bound) {
  Nearest out;
  const Vec3 d = p - p1;
  const double lambda = d.dot(u);
  const Vec3 e = unit_or(d - lambda * u, any_perpendicular(u));
  const bool at_max = bound.above(lambda, l1, l2);
  const bool at_min = !at_max && bound.below(lambda, l1, l2);
  const double clamped = at_max ? l2 : at_min ? l1 : std::clamp(lambda, l1, l2);
  out.q = p1 + clamped * u + radius * e;
  out.normals[0] = e;
  out.rows = 1;
  if (at_max || at_min) {
    out.normals[1] = u;
    out.rows = 2;
    out.at_limit = true;
  }
  return out;
}

}  // namespace dispcon
