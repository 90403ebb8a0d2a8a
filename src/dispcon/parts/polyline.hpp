// "Point to curve" on a sampled curve (seed 4.1.3, format.md `polyline`): P2 on the polyline
// through v0, v1, ... of object1. The nearest point is the nearest over the segments. On a segment:
// the two directions perpendicular to it are constrained; at the first or last vertex, all three
// (the curve's ends are limits); at an inner vertex, the two perpendicular to the mean tangent.
#pragma once

#include <vector>

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

Nearest nearest_on_polyline(const std::vector<Vec3>& vertices, const Vec3& p, BoundTest bound = {});

}  // namespace dispcon
