// Diagnostics: degrees of freedom, redundant and conflicting constraints, limits in contact
// (from the rank of the constraints' Jacobian at the solution), and range-of-motion sweeps.
#pragma once

#include <string>
#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {

struct CheckResult {
  SolveResult solve;                   // the assembly it checked (from the model's poses)
  int dof = 0;                         // mechanism degrees of freedom at the assembled pose
  std::vector<int> body_dof;           // per body (index BodyId::value); 0 for fixed bodies
  std::vector<JointId> redundant;      // consistent but superfluous
  std::vector<JointId> conflicting;    // cannot hold together with the rest
  std::vector<JointId> limits_active;  // a bound in contact
  std::vector<JointId> locking;        // couplings of a locked mechanism whose removal frees it
                                       // (gear paths with different ratios)
  std::vector<std::string> advice;  // e.g. "removing joint 3 (line 12) makes the model consistent"
  std::string message;
};

// Assembles a copy of the model, then analyses it. The model is not changed.
CheckResult check(const Model& model, const SolveOptions& options = {});

// Range of motion: turn `body` about `axis` (world, through its centre) from its assembled pose
// by angles from `from` to `to` (radians) in `steps` steps, dragging the rest along.
struct SweepOptions {
  BodyId body;
  Vec3 axis = Vec3::UnitZ();
  double from = 0;
  double to = 2 * kPi;
  int steps = 360;
  SolveOptions solve;
};

struct SweepSample {
  double value = 0;  // the driven angle
  bool converged = true;
  double max_residual = 0;
  std::vector<JointId> limits_active;
  std::vector<double>
      joint_values;  // per joint: its angle (angle part) or travel (guide), NaN if none
  std::vector<Pose> poses;
};

struct SweepResult {
  std::vector<SweepSample> samples;  // up to and including the first sample that locked
  bool locked = false;
  double lock_value = 0;  // the last driven angle reached before the lock
  std::string message;
};

constexpr int kMaxSweepSteps = 1000000;

// Throws std::invalid_argument (a ValueError naming the option) for a zero or non-finite axis,
// a non-finite or out of range angle, steps outside [1, kMaxSweepSteps], or bad solve options.
void validate(const SweepOptions& options);

SweepResult sweep(const Model& model, const SweepOptions& options);

}  // namespace dispcon
