// Rotation vectors: the exponential and logarithm maps against closed forms.
#include "dispcon/math/rotation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace dispcon {
namespace {

TEST(Rotation, ExpMatchesAngleAxis) {
  for (const Vec3& r :
       {Vec3(0.3, -0.2, 0.9), Vec3(0, 0, 3.1), Vec3(1e-9, 2e-9, 0), Vec3(2, 1, -1)}) {
    const Mat3 expected =
        Eigen::AngleAxisd(r.norm(), r.norm() > 0 ? Vec3(r.normalized()) : Vec3::UnitX())
            .toRotationMatrix();
    EXPECT_LT((quat_from_rotation_vector(r).toRotationMatrix() - expected).norm(), 1e-14);
  }
}

TEST(Rotation, LogInvertsExpForAnglesBelowPi) {
  for (const Vec3& r :
       {Vec3(0.3, -0.2, 0.9), Vec3(0, 0, 3.1), Vec3(1e-9, 2e-9, 0), Vec3(-1, 0.5, 2)}) {
    EXPECT_LT((rotation_vector_from_quat(quat_from_rotation_vector(r)) - r).norm(), 1e-12);
  }
  // The shortest arc: a turn of 2 pi - 0.1 about z is a turn of -0.1.
  const Vec3 back =
      rotation_vector_from_quat(quat_from_rotation_vector(Vec3(0, 0, 2 * M_PI - 0.1)));
  EXPECT_NEAR(back.z(), -0.1, 1e-12);
}

TEST(Rotation, SkewIsTheCrossProduct) {
  const Vec3 w(0.3, -1.2, 2.0), a(-0.7, 0.1, 0.4);
  EXPECT_LT((skew(w) * a - w.cross(a)).norm(), 1e-15);
}

TEST(Rotation, PoseMapsLocalToWorld) {
  const Pose p = Pose::from(Vec3(1, 2, 3), Vec3(0, 0, M_PI / 2));
  EXPECT_LT((p.apply(Vec3(1, 0, 0)) - Vec3(1, 3, 3)).norm(), 1e-15);
}

}  // namespace
}  // namespace dispcon
