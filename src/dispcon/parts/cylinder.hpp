// "Point to surface" on a cylinder (seed 4.1.3, format.md `cylinder`): P2 on the cylinder of axis
// P1 + lambda u, radius R, lambda in [l1, l2]. The nearest point is P1 + clamp(lambda) u + R e, e
// the unit radial direction of P2. Constrained: e; at an end of the axis range, also u.
#pragma once

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

Nearest nearest_on_cylinder(const Vec3& p1, const Vec3& u, double radius, double l1, double l2,
                            const Vec3& p, BoundTest bound = {});

}  // namespace dispcon
