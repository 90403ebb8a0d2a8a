#include "dispcon/parts/same_rotation.hpp"

#include <algorithm>
#include <cmath>

namespace dispcon {

Vec3 rotation_between(const Quat& q1, const Quat& q2) {
  return rotation_vector_from_quat(q2 * q1.conjugate());
}

void same_rotation_rotations(const Quat& q1, const Quat& q2, const Mobility& b1, const Mobility& b2,
                             Vec3& dR1, Vec3& dR2) {
  const Vec3 phi = rotation_between(q1, q2);
  const double theta = phi.norm();
  if (theta == 0) return;
  opposite_turns(phi / theta, theta, b1, b2, dR1, dR2);
}

PartRows same_rotation_rows(const Quat& q1, const Quat& q2, bool jacobian) {
  PartRows out;
  const Vec3 phi = rotation_between(q1, q2);
  out.count = 3;
  for (int k = 0; k < 3; ++k) out.residual[k] = phi[k];
  if (!jacobian) return out;
  const double theta = phi.norm();
  // H^(1/2): 1 along phi, sqrt((theta / 2) cot(theta / 2)) across it (1 at theta = 0, 0 at pi).
  const double half = 0.5 * theta;
  const double across =
      theta < 1e-4 ? 1 - theta * theta / 24 : std::sqrt(std::max(0.0, half / std::tan(half)));
  const Vec3 n = theta > 0 ? Vec3(phi / theta) : Vec3(Vec3::Zero());
  const Mat3 root = across * Mat3::Identity() + (1 - across) * n * n.transpose();
  const Mat3 E = (q2 * q1.conjugate()).toRotationMatrix();
  const Mat3 J1 = -root * E;
  for (int k = 0; k < 3; ++k) {
    out.J[k].setZero();
    out.J[k].segment<3>(0) = J1.row(k);
    out.J[k].segment<3>(6) = root.row(k);
  }
  return out;
}

}  // namespace dispcon
