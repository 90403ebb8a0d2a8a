// The seed's iteration (seed 3.2) over one group, in its two orders: Jacobi (every joint
// proposes from the same poses, the proposals are weighted by 1/max(n_i, n_j) and summed) and
// Gauss-Seidel (each joint's correction is applied at once). Internal to the solver.
#pragma once

#include "dispcon/solve/group.hpp"

namespace dispcon {

void jacobi_iteration(SolverState& s, const Group& group, const SolveOptions& o);
void gauss_seidel_iteration(SolverState& s, const Group& group, const SolveOptions& o);

}  // namespace dispcon
