// The options' door and the results' vocabulary.
#include <string>

#include "dispcon/solve/solver.hpp"

namespace dispcon {

const char* to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::Converged:
      return "converged";
    case SolveStatus::IterationLimit:
      return "iteration-limit";
    case SolveStatus::Stalled:
      return "stalled";
    case SolveStatus::Diverged:
      return "diverged";
    case SolveStatus::OutOfReach:
      return "out-of-reach";
  }
  return "?";
}

void validate(const SolveOptions& o) {
  auto positive = [](double v, const char* name) {
    check_number(v, name, name);
    if (!(v > 0))
      throw ValueError(name, std::string(name) + " " + format_number(v) + " must be positive");
  };
  positive(o.tolerance, "tolerance");
  if (o.max_iterations < 1) {
    throw ValueError("max_iterations",
                     "max_iterations " + std::to_string(o.max_iterations) + " must be at least 1");
  }
  check_number(o.time, "time", "time");
  positive(o.relaxation, "relaxation");
  positive(o.max_rotation_step, "max_rotation_step");
  check_number(o.polish_below, "polish_below", "polish_below");
  if (o.polish_below < 0) throw ValueError("polish_below", "polish_below must not be negative");
  if (o.threads < 0) throw ValueError("threads", "threads must not be negative");
}

std::vector<JointId> SolveResult::violated() const {
  std::vector<JointId> out;
  for (const ConstraintReport& c : constraints) {
    if (!c.satisfied) out.push_back(c.joint);
  }
  return out;
}

}  // namespace dispcon
