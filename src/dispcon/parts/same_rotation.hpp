// Same rotation (engine-internal, not in the format: Dragger::turn's target rotation): S2's
// rotation held equal to S1's, measured by the angle of the rotation between them. With
// E = R2 R1^T (world) and phi = log E its rotation vector (angle theta = |phi| in [0, pi]), the
// rows are phi itself, so half their squared sum is theta^2 / 2: a pull toward the joint gets
// nearer exactly as the angle between the rotations falls, all the way to pi. (An angle part
// with max 0 and a twist measure the tilt of one axis by its sine, which falls again past a
// right angle: a pull by them was drawn toward the far end of a tilt.)
//
// Rows: the residuals are phi; for world rotation vectors dR1, dR2 of the bodies E becomes
// exp(dR2 - E dR1) E to first order, and theta^2 / 2 has there the gradient phi and the Hessian
// H = n n^T + (theta / 2) cot(theta / 2) (I - n n^T), n = phi / theta. The rows' Jacobian is
// H^(1/2) (1 along n, the root of (theta / 2) cot(theta / 2) across it) on dR2 - E dR1: J^T r
// is the gradient and J^T J the Hessian, so a Gauss-Newton step on these rows is Newton's on the
// angle. (The rows of phi's own first order, Jl^-1(phi), give J^T J = |Jl^-1|^2, which across n
// is (theta / 2)^2 / sin^2(theta / 2) against the true (theta / 2) cot(theta / 2): 2.2 times too
// stiff at 2 rad, and without bound toward pi, so a pull's steps fell short.)
// Correction: opposite angular impulses tau n about n = phi / theta that close theta (as the
// angle part's, conserving the pair's angular momentum).
#pragma once

#include "dispcon/parts/part.hpp"

namespace dispcon {

// The rotation vector of q2 q1^-1 (world frame), its angle in [0, pi].
Vec3 rotation_between(const Quat& q1, const Quat& q2);

void same_rotation_rotations(const Quat& q1, const Quat& q2, const Mobility& b1, const Mobility& b2,
                             Vec3& dR1, Vec3& dR2);

// Three rows, always (the residual is 0 only where the rotations are the same).
PartRows same_rotation_rows(const Quat& q1, const Quat& q2, bool jacobian = true);

}  // namespace dispcon
