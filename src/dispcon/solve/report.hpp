// What a solve says: one report per joint, and the one line for people. Internal to the solver.
#pragma once

#include <string>
#include <vector>

#include "dispcon/solve/counted.hpp"
#include "dispcon/solve/state.hpp"

namespace dispcon {

// "joint 3 (line 12) crank / coupler residual 0.25"
std::string describe(const Model& model, const ConstraintReport& c);

// Every joint at the state's poses; `known`, when given, holds every joint's residual there.
std::vector<ConstraintReport> report(const SolverState& s, double tolerance,
                                     const std::vector<double>* known = nullptr);

// The joints a result leaves unsatisfied, the largest residual first (a non-finite one ranked as
// infinite), in the joints' order among equals.
std::vector<ConstraintReport> violated_worst_first(const std::vector<ConstraintReport>& all);

// The one line: what happened and the joints at fault (the worst five).
std::string solve_message(const Model& model, const SolveResult& result);

}  // namespace dispcon
