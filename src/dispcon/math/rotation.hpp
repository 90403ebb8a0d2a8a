// Rotation vectors and poses.
//
// The seed (section 2.2, eq. 4) writes small rotations as rotation vectors: the axis times the
// angle. We keep orientations as unit quaternions (renormalised after every update, the seed's
// "re-orthogonalised" matrix) and convert rotation vectors exactly with the exponential map, so a
// large rotation vector is still a proper rotation.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace dispcon {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// exp: rotation vector (axis * angle, radians) -> unit quaternion.
Quat quat_from_rotation_vector(const Vec3& r);
// log: unit quaternion -> rotation vector with angle in [0, pi].
Vec3 rotation_vector_from_quat(const Quat& q);
// [w]x such that skew(w) * a = w x a.
Mat3 skew(const Vec3& w);

// A rigid placement: a local point p is at R p + x in the world.
struct Pose {
  Quat q = Quat::Identity();
  Vec3 x = Vec3::Zero();

  Mat3 rotation() const { return q.toRotationMatrix(); }
  Vec3 apply(const Vec3& local) const { return q * local + x; }
  Vec3 rotation_vector() const { return rotation_vector_from_quat(q); }
  static Pose from(const Vec3& position, const Vec3& rotation_vector) {
    return Pose{quat_from_rotation_vector(rotation_vector), position};
  }
};

// True when both lists hold the same poses bit for bit: what a failed solve, drag step or
// animation frame promises to leave behind (checked by the tests and by the fuzz oracle).
bool same_bits(const std::vector<Pose>& a, const std::vector<Pose>& b);

}  // namespace dispcon
