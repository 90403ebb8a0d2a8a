// The small interface every constraint part shares (house style 2): a part proposes small
// rotations and translations of its two bodies, and gives its Jacobian rows and residuals for the
// Newton polish and for diagnostics.
//
// Jacobian columns (12): the rotation vector of body 1 about its centre G1, the translation of G1,
// the same two for body 2; world coordinates, as the seed's dR and dx.
#pragma once

#include <Eigen/Core>

#include "dispcon/math/rotation.hpp"

namespace dispcon {

using Row = Eigen::Matrix<double, 1, 12>;

// How one body of a pair takes corrections, in world coordinates.
struct Mobility {
  Vec3 G = Vec3::Zero();  // centre of rotation
  Mat3 A = Mat3::Zero();  // rotation per unit moment: mu12 * k (no physics) or mu12 m J^-1
  double mu = 0;          // share of a translation (mu12 for body 1, 1 - mu12 for body 2)
};

// Up to three rows of one part.
struct PartRows {
  int count = 0;
  Row J[3];
  double residual[3] = {0, 0, 0};
  bool at_limit = false;
};

}  // namespace dispcon
