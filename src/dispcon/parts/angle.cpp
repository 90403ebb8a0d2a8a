#include "dispcon/parts/angle.hpp"

#include <algorithm>
#include <cmath>

#include "dispcon/model/joint.hpp"

namespace dispcon {

namespace {

// The bound a violated (or touching) angle is held to; NaN when neither is in contact. The
// angle is measured (`theta()`) only when an equality does not decide.
template <typename Angle>
double active_bound(Angle&& theta, double min, double max, BoundTest bound) {
  // 0 and pi are the natural ends of the range: only a real bound can be in contact.
  if (max < kPi && (max == 0 || min == max || theta() >= max - bound.band)) return max;
  if (min > 0 && (min == kPi || theta() <= min + bound.band)) return min;
  return std::nan("");
}

Vec3 rotation_axis(const Vec3& a1, const Vec3& a2) {
  return unit_or(a1.cross(a2), any_perpendicular(a1));
}

}  // namespace

double angle_between(const Vec3& a1, const Vec3& a2) {
  return std::atan2(a1.cross(a2).norm(), a1.dot(a2));
}

double angle_violation(const Vec3& a1, const Vec3& a2, double min, double max) {
  const double theta = angle_between(a1, a2);
  return std::abs(theta - std::clamp(theta, min, max));
}

void angle_rotations(const Vec3& a1, const Vec3& a2, double min, double max, const Mobility& b1,
                     const Mobility& b2, Vec3& dR1, Vec3& dR2) {
  const double theta = angle_between(a1, a2);
  const double delta = theta - std::clamp(theta, min, max);
  if (delta == 0) return;
  opposite_turns(rotation_axis(a1, a2), delta, b1, b2, dR1, dR2);
}

PartRows angle_rows(const Vec3& a1, const Vec3& a2, double min, double max, BoundTest bound,
                    bool jacobian) {
  PartRows out;
  // An angle held at 0 or pi (a hinge's axes) needs no angle, only the axes' cross product: an
  // atan2 less per joint and pass.
  double theta = std::nan("");
  auto angle = [&] {
    if (std::isnan(theta)) theta = angle_between(a1, a2);
    return theta;
  };
  const double b = active_bound(angle, min, max, bound);
  if (std::isnan(b)) return out;
  out.at_limit = !(min == max);
  if (b > 1e-6 && b < kPi - 1e-6) {
    out.count = 1;
    out.residual[0] = angle() - b;
    if (!jacobian) return out;
    const Vec3 n = rotation_axis(a1, a2);
    out.J[0].setZero();
    out.J[0].segment<3>(0) = -n.transpose();
    out.J[0].segment<3>(6) = n.transpose();
    return out;
  }
  // Bound 0 or pi: c = a1 x a2 must vanish. For a direction e,
  //   d(e . c) = dR1 . ((e.a1) a2 - (a1.a2) e) + dR2 . ((a1.a2) e - (e.a2) a1).
  Vec3 e[2];
  orthonormal_basis(a1, e[0], e[1]);
  const Vec3 c = a1.cross(a2);
  const double cos = a1.dot(a2);
  out.count = 2;
  for (int k = 0; k < 2; ++k) {
    out.residual[k] = e[k].dot(c);
    if (!jacobian) continue;
    out.J[k].setZero();
    out.J[k].segment<3>(0) = (e[k].dot(a1) * a2 - cos * e[k]).transpose();
    out.J[k].segment<3>(6) = (cos * e[k] - e[k].dot(a2) * a1).transpose();
  }
  return out;
}

}  // namespace dispcon
