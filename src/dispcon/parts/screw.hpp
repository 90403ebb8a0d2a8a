// Screw coupling (issue 11): with a cylindrical pair in the same constraint (hinge, axial, angle
// a a max 0), object2's travel along the axis is pitch / (2 pi) times its turn relative to
// object1, right-handed (a left-handed screw travels the other way).
//
// Object1 (the nut, or the frame): axis n = R1 a1 through C1 = R1 c1 + x1, reference r1 = R1 b1.
// Object2 (the screw): axis R2 a2 through C2 = R2 c2 + x2, reference r2 = R2 b2 (b_i fixed unit
// vectors across a_i).
//   travel  s = (C2 - C1) . n
//   turn    theta = atan2((r1 x r2) . n2, r1 . r2)   (object2's turn relative to object1)
//   s - hand pitch / (2 pi) theta = phase,   hand = +1 (right) or -1 (left).
// Row: ds - hand pitch / (2 pi) d theta with
//   ds = -dR1 . ((C2 - G1) x n) - n . dx1 + dR2 . ((C2 - G2) x n) + n . dx2
// and d theta from turn() with dr1 = dR1 x r1. Both are relative measures, so the correction is a
// pair of opposite impulses (coupling.hpp).
#pragma once

#include "dispcon/parts/coupling.hpp"

namespace dispcon {

CouplingMeasure measure_screw(const CouplingSpec& c, const Frame& f1, const Frame& f2,
                              bool with_rows);

}  // namespace dispcon
