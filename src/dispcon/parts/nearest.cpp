#include "dispcon/parts/nearest.hpp"

#include <cmath>

namespace dispcon {

Vec3 any_perpendicular(const Vec3& u) {
  const Vec3 other = std::abs(u.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  return u.cross(other).normalized();
}

Vec3 unit_or(const Vec3& v, const Vec3& fallback) {
  const double n = v.norm();
  return n > 1e-300 ? Vec3(v / n) : fallback;
}

}  // namespace dispcon
