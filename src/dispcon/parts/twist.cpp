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
                    double max, BoundTest bound, bool jacobian, bool tilted) {
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
  if (!tilted) {
    out.J[0].segment<3>(0) = -h.transpose();
    out.J[0].segment<3>(6) = h.transpose();
    return out;
  }
  // The twist's whole first order, for axes apart: with body i turned by dRi (a_i, b_i turned
  // with it: d v = dRi x v = -[v]x dRi), the bisector h = s / |s| (s = a1 + a2) turns too, and
  // the twist atan2(y, x), y = h . (p1 x p2), x = p1 . p2, moves by (x dy - y dx) / (x^2 + y^2).
  // Measured by h . (dR2 - dR1) alone, a ball joint's twist at its limit with its cone tilted was
  // met only to first order in the tilt: the corrections after each step converged linearly and
  // a pull along the two limits' corner stopped short of its least point (the robot arm's hand
  // turned 1.5 rad about (1, 1, 1): 1.9e-4 rad short).
  const double length = (a1 + a2).norm();
  const Mat3 across = (Mat3::Identity() - h * h.transpose()) / length;
  const Vec3 p1 = b1 - b1.dot(h) * h, p2 = b2 - b2.dot(h) * h;
  const double x = p1.dot(p2), y = h.dot(p1.cross(p2));
  const Vec3 y_h = p1.cross(p2), y_p1 = p2.cross(h), y_p2 = h.cross(p1);
  for (int side = 0; side < 2; ++side) {
    const Vec3& a = side == 0 ? a1 : a2;
    const Vec3& b = side == 0 ? b1 : b2;
    const Vec3& b_other = side == 0 ? b2 : b1;
    const Mat3 dh = across * -skew(a);  // d h / d dRi
    const Mat3 db = -skew(b);
    // d p (this side's) and d p_other (its b does not turn with this body, only h does).
    const Mat3 dp = db - h * (h.transpose() * db) - h * (b.transpose() * dh) - b.dot(h) * dh;
    const Mat3 dq = -h * (b_other.transpose() * dh) - b_other.dot(h) * dh;
    const Mat3& dp1 = side == 0 ? dp : dq;
    const Mat3& dp2 = side == 0 ? dq : dp;
    const Eigen::RowVector3d dx = p2.transpose() * dp1 + p1.transpose() * dp2;
    const Eigen::RowVector3d dy =
        y_h.transpose() * dh + y_p1.transpose() * dp1 + y_p2.transpose() * dp2;
    out.J[0].segment<3>(side == 0 ? 0 : 6) = (x * dy - y * dx) / (x * x + y * y);
  }
  return out;
}

}  // namespace dispcon
