#include "dispcon/parts/segment.hpp"

#include <algorithm>

namespace dispcon {

Nearest nearest_on_segment(const Vec3& p1, const Vec3& u, double l1, double l2, const Vec3& p,
                           BoundTest bound) {
  Nearest n;
  const double lambda = (p - p1).dot(u);
  const bool at_max = bound.above(lambda, l1, l2);
  const bool at_min = !at_max && bound.below(lambda, l1, l2);
  n.at_limit = at_max || at_min;
  const double clamped = at_max ? l2 : at_min ? l1 : std::clamp(lambda, l1, l2);
  n.q = p1 + clamped * u;
  if (n.at_limit) {
    n.rows = 3;
    n.normals = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  } else {
    n.rows = 2;
    const Vec3 off = p - n.q;
    n.normals[0] = unit_or(off - off.dot(u) * u, any_perpendicular(u));
    n.normals[1] = u.cross(n.normals[0]);
  }
  return n;
}

}  // namespace dispcon
