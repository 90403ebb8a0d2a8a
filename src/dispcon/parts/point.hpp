// "Point to point" (seed 3): P2 coincides with P1. The permissible set is the single point P1, so
// the nearest point is P1 and all three directions are constrained.
#pragma once

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

// Inline: every look at a hinge's or a ball's geometry takes it (SolverState::geometry), where
// the call and the copy of its answer out of the callee's frame cost more than the answer.
inline Nearest nearest_on_point(const Vec3& p1, const Vec3& /*p*/) {
  Nearest n;
  n.q = p1;
  n.rows = 3;
  n.normals = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  return n;
}

}  // namespace dispcon
