// "Point to segment" (seed 4.1.1, format.md `axial`): P2 = P1 + lambda u, lambda in [l1, l2]
// (either bound may be infinite). The nearest point is P1 + clamp((P2 - P1) . u, l1, l2) u.
// Inside the segment the two directions perpendicular to u are constrained; at an end, all three.
#pragma once

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

Nearest nearest_on_segment(const Vec3& p1, const Vec3& u, double l1, double l2, const Vec3& p,
                           BoundTest bound = {});

}  // namespace dispcon
