// What every translation guide answers (seed 4.1: "P2 is replaced ... with the point P'2 of the
// permissible set that is the closest"): the nearest permissible point and the directions in which
// the set constrains a point there (its normal space), all in object1's local frame.
#pragma once

#include <array>
#include <cmath>

#include "dispcon/math/rotation.hpp"

namespace dispcon {

struct Nearest {
  Vec3 q = Vec3::Zero();          // nearest permissible point
  int rows = 0;                   // how many constrained directions at q (0 to 3)
  std::array<Vec3, 3> normals{};  // orthonormal, the first `rows` are used
  bool at_limit = false;          // a bound (segment end, ring edge, ...) is in contact
};

// Two unit vectors that make an orthonormal basis with `first` (unit), as a smooth function of
// `first` except across first.z() = -1 (Duff et al., "Building an orthonormal basis, revisited",
// 2017): one division, no square root. A hinge's angle rows take one at every pass over the
// joints, where normalising a cross product (a square root and three divisions in a chain) was
// a tenth of a grid's drag step. Inline: called from the parts' rows.
inline void orthonormal_basis(const Vec3& first, Vec3& second, Vec3& third) {
  const double sign = std::copysign(1.0, first.z());
  const double a = -1.0 / (sign + first.z());
  const double b = first.x() * first.y() * a;
  second = Vec3(1.0 + sign * first.x() * first.x() * a, sign * b, -sign * first.x());
  third = Vec3(b, sign + first.y() * first.y() * a, -first.y());
}

// Any unit vector perpendicular to the unit vector u.
Vec3 any_perpendicular(const Vec3& u);

// Unit vector along v, or `fallback` when v is (nearly) zero.
Vec3 unit_or(const Vec3& v, const Vec3& fallback);

// When a bound counts as in contact: `band` widens contact to values within it of the bound
// (diagnostics use the tolerance); a negative band counts only values beyond the bound by more
// than -band (the Newton polish, so that a joint resting on its limit may leave it). A bound with
// min = max is an equality and always in contact.
struct BoundTest {
  double band = 0;
  bool above(double value, double min, double max) const {
    return max < kHuge && (value >= max - band || min == max);
  }
  bool below(double value, double min, double max) const {
    return min > -kHuge && (value <= min + band || min == max);
  }
  static constexpr double kHuge = 1e300;
};

}  // namespace dispcon
