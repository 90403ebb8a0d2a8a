#include "dispcon/parts/point.hpp"

namespace dispcon {

Nearest nearest_on_point(const Vec3& p1, const Vec3& /*p*/) {
  Nearest n;
  n.q = p1;
  n.rows = 3;
  n.normals = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  return n;
}

}  // namespace dispcon
