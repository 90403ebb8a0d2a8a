// A pull (Session::pull): one joint of a group is soft, the others hard; the group moves so
// that the soft joint's residual is as small as the hard joints allow. Internal to the solver.
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include "dispcon/solve/polish.hpp"
#include "dispcon/solve/rim.hpp"

namespace dispcon {

struct PullOutcome {
  int iterations = 0;       // Newton steps taken (pull steps and corrections)
  bool holds = false;       // the hard joints hold within the tolerance at the poses left
  double distance = 0;      // the soft joint's residual there
  double hard = 0;          // the hard joints' largest residual there
  bool stationary = false;  // stopped because no step gets nearer (else: reached, or the cap)
};

// A pull's scratch, the session's: a warm pull's steps allocate nothing in it (a turn's model,
// and its steps, made 261-311 allocations a drag step until issue 14's fifteenth round). Each
// pull starts its model again. The model is made at the first turn (its matrices of fixed
// capacity take half a megabyte, which a session that never turns should not carry).
struct PullWork {
  std::unique_ptr<RimModel> rim;
  std::vector<PolishWork::Vec6> dq, rim_dq;  // a pull step's and a reduced step's
};

// Pulls from the group's current poses (they are left at the nearest poses found; where the hard
// joints cannot be made to hold, at those given). `soft` has one entry per joint, all zero; it is
// used as scratch for the pull joint's damping; `before`, `spare` and `valid` hold poses aside
// (the caller's, so that a warm pull allocates none: `valid` was one allocation a turn's pull);
// `pw` is the rest of its scratch.
// `max_iterations` caps the Newton steps. `follows`: the last pull of this joint reached its
// target (a drag in reach, frame after frame): the first step is then damped less. `most`
// bounds every iteration, the corrections made past the cap included (the poses a pull leaves
// are corrected back onto the joints past it, up to kCorrections Newton steps, unless `most`
// comes first): where the joints do not hold by then, the pull ends at the last pose it kept at
// which they did (no nearest claimed).
PullOutcome pull_group(SolverState& s, const Group& group, int joint, Polisher& polisher,
                       PolishWork& work, std::vector<double>& band, const SolveOptions& o,
                       std::vector<double>& soft, PoseBuffer& before, PoseBuffer& spare,
                       PoseBuffer& valid, PullWork& pw, std::vector<double>& joint_r,
                       bool follows = false, int most = std::numeric_limits<int>::max());

}  // namespace dispcon
