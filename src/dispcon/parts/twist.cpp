#include "dispcon/parts/twist.hpp"

#include <cmath>

#include "dispcon/model/joint.hpp"

namespace dispcon {

namespace {

double wrap(double a) {
  return std::remainder(a, 2 * kPi);
}

bool bisector(const Vec3& a1, const Vec3& a2, Vec3& h) {
  const Vec3 s = a1 + a2;
  const double n = s.norm();
  if (n < 1e-9) return false;
  h = s / n;
  return true;
}

}  // namespace

double twist_angle(const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2) {
  Vec3 h;
  if (!bisector(a1, a2, h)) return std::nan("");
  const Vec3 p1 = b1 - b1.dot(h) * h;
  const Vec3 p2 = b2 - b2.dot(h) * h;
  return std::atan2(p1.cross(p2).dot(h), p1.dot(p2));
}

double twist_violation(double twist, double min, double max) {
  if (std::isnan(twist)) return 0;
  if (min <= -kPi && max >= kPi) return 0;
  if (twist >= min && twist <= max) return 0;
  const double to_min = wrap(twist - min);
  const double to_max = wrap(twist - max);
  return std::abs(to_min) < std::abs(to_max) ? to_min : to_max;
}

void twist_rotations(const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2, double min,
                     double max, const Mobility& body1, const Mobility& body2, Vec3& dR1,
                     Vec3& dR2) {
  Vec3 h;
  if (!bisector(a1, a2, h)) return;
  const double delta = twist_violation(twist_angle(a1, a2, b1, b2), min, max);
  if (delta == 0) return;
  opposite_turns(h, delta, body1, body2, dR1, dR2);
}

PartRows twist_rows(const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2, double min,
                    double max, BoundTest bound, bool jacobian) {
  PartRows out;
  Vec3 h;
  if (!bisector(a1, a2, h)) return out;
  if (min <= -kPi && max >= kPi) return out;
  const double twist = twist_angle(a1, a2, b1, b2);
  const double violation = twist_violation(twist, min, max);
  const bool upper = max < kPi && (twist >= max - bound.band || min == max);
  const bool lower = !upper && min > -kPi && twist <= min + bound.band;
  if (violation == 0 && !upper && !lower) return out;
  const double residual = violation != 0 ? violation : upper ? twist - max : twist - min;
  out.count = 1;
  out.at_limit = min != max;
  out.residual[0] = residual;
  if (!jacobian) return out;
  out.J[0].setZero();
  out.J[0].segment<3>(0) = -h.transpose();
  out.J[0].segment<3>(6) = h.transpose();
  return out;
}

}  // namespace dispcon
