// SolveSpace's C header (it uses memset without including <cstring>), and running a system.
#pragma once

// clang-format off
#include <cstring>
#include <slvs.h>
// clang-format on

#include <vector>

namespace bench {

// Solves group `group` of a SolveSpace system given as three arrays (values updated in place);
// returns SolveSpace's result code.
inline int solve_slvs(std::vector<Slvs_Param>& param, std::vector<Slvs_Entity>& entity,
                      std::vector<Slvs_Constraint>& constraint, Slvs_hGroup group) {
  Slvs_System sys = {};
  sys.param = param.data();
  sys.params = static_cast<int>(param.size());
  sys.entity = entity.data();
  sys.entities = static_cast<int>(entity.size());
  sys.constraint = constraint.data();
  sys.constraints = static_cast<int>(constraint.size());
  std::vector<Slvs_hConstraint> failed(constraint.size());
  sys.failed = failed.data();
  sys.faileds = static_cast<int>(failed.size());
  Slvs_Solve(&sys, group);
  return sys.result;
}

}  // namespace bench
