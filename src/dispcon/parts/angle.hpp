// Angle constraints (seed 4.2.1): the angle theta between a1 (of S1) and a2 (of S2), world frame,
// kept in [min, max] within [0, pi]. min = max puts a2 on a cone about a1; max = 0 aligns them.
//
// When theta leaves the interval, rotations in the plane (a1, a2) are added, i.e. about
// n = a1 x a2 / |a1 x a2|. Since d theta = n . (dR2 - dR1), opposite angular impulses tau n give
//   dR1 = +tau A1 n,  dR2 = -tau A2 n,  tau = (theta - clamp(theta)) / (n.A1 n + n.A2 n)
// which closes the violation in one step for scalar abilities and conserves the pair's angular
// momentum (A = mu K, the inertia in the physics variant, as the seed asks).
// Rows: one, n . (dR2 - dR1), for a bound inside (0, pi); two when the bound is 0 or pi (the
// components of a1 x a2 across a1, since n is undefined there).
#pragma once

#include "dispcon/parts/nearest.hpp"
#include "dispcon/parts/part.hpp"

namespace dispcon {

double angle_between(const Vec3& a1, const Vec3& a2);

// Distance from the angle to [min, max] (0 when inside).
double angle_violation(const Vec3& a1, const Vec3& a2, double min, double max);

// Adds the correcting rotations to dR1, dR2; nothing when the angle is within bounds.
void angle_rotations(const Vec3& a1, const Vec3& a2, double min, double max, const Mobility& b1,
                     const Mobility& b2, Vec3& dR1, Vec3& dR2);

// Rows of the bound in contact (or violated); none when the angle is strictly inside.
PartRows angle_rows(const Vec3& a1, const Vec3& a2, double min, double max, BoundTest bound = {},
                    bool jacobian = true);

}  // namespace dispcon
