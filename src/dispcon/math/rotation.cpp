#include "dispcon/math/rotation.hpp"

#include <cmath>
#include <cstring>

namespace dispcon {

Quat quat_from_rotation_vector(const Vec3& r) {
  const double angle = r.norm();
  if (angle < 1e-12) {
    // Second-order series: exact to rounding for such small angles.
    Quat q(1.0, 0.5 * r.x(), 0.5 * r.y(), 0.5 * r.z());
    return q.normalized();
  }
  const double s = std::sin(0.5 * angle) / angle;
  return Quat(std::cos(0.5 * angle), s * r.x(), s * r.y(), s * r.z());
}

Vec3 rotation_vector_from_quat(const Quat& q_in) {
  Quat q = q_in.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();  // shortest arc: angle in [0, pi]
  const Vec3 v = q.vec();
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  const double angle = 2.0 * std::atan2(s, q.w());
  return v * (angle / s);
}

Mat3 skew(const Vec3& w) {
  Mat3 m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

bool same_bits(const std::vector<Pose>& a, const std::vector<Pose>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (std::memcmp(a[i].q.coeffs().data(), b[i].q.coeffs().data(), 4 * sizeof(double)) != 0 ||
        std::memcmp(a[i].x.data(), b[i].x.data(), 3 * sizeof(double)) != 0)
      return false;
  }
  return true;
}

}  // namespace dispcon
