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

// Up to three rows of one part. The row functions take `jacobian`: false leaves J unset and
// gives the rows' residuals alone (a chord step's right-hand side), the same values and count.
struct PartRows {
  int count = 0;
  Row J[3];
  double residual[3] = {0, 0, 0};
  bool at_limit = false;
};

// Opposite angular impulses tau n on the two bodies, sized so the pair turns relatively by
// `delta` about n (to first order): dR1 += tau A1 n, dR2 -= tau A2 n, tau = delta / (n.A1 n +
// n.A2 n). Equal and opposite, so the pair's angular momentum is conserved (seed 4.2).
inline void opposite_turns(const Vec3& n, double delta, const Mobility& b1, const Mobility& b2,
                           Vec3& dR1, Vec3& dR2) {
  const Vec3 An1 = b1.A * n;
  const Vec3 An2 = b2.A * n;
  const double mobility = n.dot(An1) + n.dot(An2);
  if (mobility <= 0) return;
  const double tau = delta / mobility;
  dR1 += tau * An1;
  dR2 -= tau * An2;
}

}  // namespace dispcon
