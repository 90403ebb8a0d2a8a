// The displacements of a "point to point" constraint (seed 3.1), used by every translation part
// with P1 replaced by the nearest permissible point (seed 4.1).
//
// A rubber of stiffness k pulling P1 of S1 towards P2 of S2 gives (eqs. 5-13)
//   dR1 = m1 J1^-1 (P1 - G1) x dx1,   dx1 = (k dt^2 / 2 m1) (P2 - P1).
// The one-iteration scheme (eqs. 18-19) takes alpha = m1 m2 / (m1 + m2):
//   1. rotate:    dR1 = m1 m2/(m1+m2) J1^-1 (P1 - G1) x (P2 - P1)
//                 dR2 = m1 m2/(m1+m2) J2^-1 (P2 - G2) x (P1 - P2)                      (18)
//   2. translate, from P1', P2' after rotation:
//                 dx1 = m2/(m1+m2) (P2' - P1'),  dx2 = m1/(m1+m2) (P1' - P2')             (19)
// so the constraint holds exactly after one iteration when it is alone. Without physics (3.1.4)
// m2/(m1+m2) becomes the "ability to move" mu12 and m1 J1^-1 the "ability to rotate" k1:
//   dR1 = mu12 k1 (P1 - G1) x (P2 - P1), dx1 = mu12 (P2' - P1'), with mu21 = 1 - mu12.
// Both are written here with A1 = mu12 K1 (K1 = k1 I or m1 J1^-1, world frame).
// The forces are opposite and along P2 - P1, so the first-order linear and angular momenta of the
// pair are conserved (footnote 5) when the translations use the same P1, P2 as the rotations
// (eqs. 14-15); eq. 19 trades a little of that for exactness.
#pragma once

#include "dispcon/parts/nearest.hpp"
#include "dispcon/parts/part.hpp"

namespace dispcon {

// Eq. 18: adds the rotation vectors of bodies 1 and 2 to dR1, dR2.
void point_rotations(const Vec3& P1, const Vec3& P2, const Mobility& b1, const Mobility& b2,
                     Vec3& dR1, Vec3& dR2);

// Eq. 19: adds the translations of bodies 1 and 2 to dx1, dx2.
void point_translations(const Vec3& P1, const Vec3& P2, const Mobility& b1, const Mobility& b2,
                        Vec3& dx1, Vec3& dx2);

// Rows n . (P2 - Q) for each constrained direction n (world) of a guide's nearest point Q.
PartRows point_rows(const Vec3& Q, const Vec3& P2, const Vec3& G1, const Vec3& G2,
                    const Nearest& world_nearest, bool jacobian = true);

}  // namespace dispcon
