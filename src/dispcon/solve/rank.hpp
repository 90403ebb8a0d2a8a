// The rank of the constraints' Jacobian at a model's poses, for `dispcon check`: degrees of
// freedom, each body's freedoms, and the joints whose equations repeat those before them.
// Internal to the engine (diagnostics and its tests).
//
// Bodies joined by no chain of joints are independent: the Jacobian is block diagonal over the
// solver's groups (find_groups), so its rank is the sum of theirs and each group is ranked on its
// own small dense block. A thousand four-bars are a thousand 20 x 18 blocks, not one 20,000 x
// 18,000 matrix (cubic time and gigabytes).
#pragma once

#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {

struct Repeated {
  JointId joint;
  int equations = 0;  // of its rows
  int repeated = 0;   // how many of them repeat those of the joints before it (> 0)
};

struct RankReport {
  int dof = 0;
  std::vector<int> body_dof;        // per body (index BodyId::value); 0 for fixed bodies
  std::vector<Repeated> redundant;  // in model order
};

// Group by group. The rank tolerance is relative to each group's largest singular value, so a
// group's answer does not depend on what else is in the model.
RankReport rank_by_group(const Model& model, const SolveOptions& options);

// The whole Jacobian at once, as one dense block: the reference rank_by_group() is tested
// against (cubic in the model's size; for tests and small models only).
RankReport rank_whole(const Model& model, const SolveOptions& options);

}  // namespace dispcon
