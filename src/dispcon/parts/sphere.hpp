// "Point in sphere" (seed 4.1.3, format.md `sphere`): |P2 - P1| in [r1, r2]: on a sphere when
// r1 = r2, in a ball when r1 = 0, in a shell otherwise. Inside, nothing is constrained; on a
// bound, the radial direction.
#pragma once

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

Nearest nearest_in_sphere(const Vec3& p1, double r1, double r2, const Vec3& p,
                          BoundTest bound = {});

}  // namespace dispcon
