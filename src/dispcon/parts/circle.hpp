// "Point to curve" on a circle (seed 4.1.3, format.md `circle`): P2 on the circle of centre P1,
// normal n, radius R. The nearest point is P1 + R e, e the unit projection of P2 - P1 on the
// circle's plane. Two directions are constrained: n and e (the tangent n x e is free).
#pragma once

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

Nearest nearest_on_circle(const Vec3& p1, const Vec3& n, double radius, const Vec3& p);

}  // namespace dispcon
