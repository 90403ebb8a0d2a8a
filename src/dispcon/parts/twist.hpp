// Twist constraints (seed 4.2.2, format.md): with the angle's axes a1, a2 and vectors b1 (of S1,
// across a1) and b2 (of S2, across a2), h = normalise(a1 + a2); b1', b2' are b1, b2 projected on
// the plane perpendicular to h; the twist is the signed angle from b1' to b2' about h, kept in
// [min, max] within [-pi, pi]. (The seed's "median plane of normal a1 - a2" is undefined for
// aligned axes; format.md takes the plane perpendicular to the bisector.)
//
// Correction: opposite angular impulses tau h turn S1 and S2 about the bisector,
//   dR1 = +tau A1 h,  dR2 = -tau A2 h,  tau = wrap(twist - target) / (h.A1 h + h.A2 h),
// which conserves the pair's angular momentum; the seed turns each solid about its own a_i, the
// same rotation when the axes are aligned (the common case, and the one of a weld, 4.2.3).
// Row: h . (dR2 - dR1), exact to first order when a1 = a2 (its whole first order where the
// angle part lets the axes tilt apart: twist_rows' `tilted`).
#pragma once

#include "dispcon/parts/nearest.hpp"
#include "dispcon/parts/part.hpp"

namespace dispcon {

// Signed twist in [-pi, pi]; NaN when a1 = -a2 (no bisector).
double twist_angle(const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2);

// Signed distance from the twist to [min, max], taken the short way round the circle.
double twist_violation(double twist, double min, double max);

void twist_rotations(const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2, double min,
                     double max, const Mobility& body1, const Mobility& body2, Vec3& dR1,
                     Vec3& dR2);

// `tilted`: the axes may stand apart (the angle part allows a tilt: a ball joint's cone), and
// the row is the twist's whole first order; else h . (dR2 - dR1), exact when they are aligned.
PartRows twist_rows(const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2, double min,
                    double max, BoundTest bound = {}, bool jacobian = true, bool tilted = false);

}  // namespace dispcon
