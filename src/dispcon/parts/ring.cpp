#include "dispcon/parts/ring.hpp"

namespace dispcon {

Nearest nearest_on_ring(const Vec3& p1, const Vec3& n, double r1, double r2, const Vec3& p,
                        BoundTest bound) {
  Nearest out;
  const Vec3 d = p - p1;
  const Vec3 in_plane = d - d.dot(n) * n;
  const double r = in_plane.norm();
  const bool at_max = bound.above(r, r1, r2);
  const bool at_min = !at_max && r1 > 0 && bound.below(r, r1, r2);
  out.normals[0] = n;
  if (!at_max && !at_min) {
    out.q = p1 + in_plane;
    out.rows = 1;
    return out;
  }
  const Vec3 radial = unit_or(in_plane, any_perpendicular(n));
  out.q = p1 + (at_max ? r2 : r1) * radial;
  out.rows = 2;
  out.normals[1] = radial;
  out.at_limit = true;
  return out;
}

}  // namespace dispcon
