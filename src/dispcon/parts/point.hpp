// "Point to point" (seed 3): P2 coincides with P1. The permissible set is the single point P1, so
// the nearest point is P1 and all three directions are constrained.
#pragma once

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

Nearest nearest_on_point(const Vec3& p1, const Vec3& p);

}  // namespace dispcon
