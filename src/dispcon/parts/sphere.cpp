#include "dispcon/parts/sphere.hpp"

namespace dispcon {

Nearest nearest_in_sphere(const Vec3& p1, double r1, double r2, const Vec3& p, BoundTest bound) {
  Nearest out;
  const Vec3 d = p - p1;
  const double r = d.norm();
  const bool at_max = bound.above(r, r1, r2);
  const bool at_min = !at_max && r1 > 0 && bound.below(r, r1, r2);
  if (!at_max && !at_min) {
    out.q = p;
    out.rows = 0;
    return out;
  }
  const Vec3 radial = unit_or(d, Vec3::UnitX());
  out.q = p1 + (at_max ? r2 : r1) * radial;
  out.rows = 1;
  out.normals[0] = radial;
  out.at_limit = true;
  return out;
}

}  // namespace dispcon
