// "Point to ring" (seed 4.1.2, format.md `planar`): P2 in the plane through P1 of normal n, at a
// distance r from P1 with r in [r1, r2]: r1 = 0 a disc, r1 > 0 a ring, r2 = inf the whole plane.
// The nearest point is the projection of P2 on the plane when it falls in the ring, else the
// point of the ring's edge nearest to that projection. Inside: one constrained direction (n); on an
// edge: two (n and the radial direction).
#pragma once

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

Nearest nearest_on_ring(const Vec3& p1, const Vec3& n, double r1, double r2, const Vec3& p,
                        BoundTest bound = {});

}  // namespace dispcon
