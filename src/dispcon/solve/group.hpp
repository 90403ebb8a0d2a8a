// Groups: the bodies that move together (joined by active joints through movable bodies) and
// the joints that touch them. Each group is an independent problem that iterates until it
// holds, so a converged part of a large assembly costs nothing while the rest works, and groups
// can be solved on several threads. Internal to the solver.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "dispcon/solve/state.hpp"

namespace dispcon {

struct Group {
  std::vector<int> bodies;  // movable bodies
  std::vector<int> joints;  // active joints touching them
};

std::vector<Group> find_groups(const SolverState& s);

// The largest violation of some joints; each joint's own goes to `store` (indexed by joint), so
// the final report need not measure again. A non-finite residual makes the result infinite
// (std::max would drop a NaN).
double max_residual(const SolverState& s, const std::vector<int>& joints,
                    std::vector<double>& store);
// The larger of a largest violation so far and one more joint's, as max_residual() folds them.
inline double larger_residual(double r, double rc) {
  return rc <= r ? r : std::isnan(rc) ? std::numeric_limits<double>::infinity() : rc;
}

// A group's size: the diagonal of the box around its bodies and its joints' points. The switch to
// Newton steps is relative to it, so a group solves the same whatever else is in the model.
double group_size(const SolverState& s, const Group& group);

// The poses a solve keeps aside (the best seen, those before a step): one per body of the model,
// on huge pages in the largest models (their first touch, a fresh 4 KB page at a time, cost
// the 100,000-link chain's solve as much as a Newton step).
using PoseBuffer = HugeVector<Pose>;

// A group's bodies' poses into `out`, or from `in` (a PoseBuffer, or the poses a solve returns).
template <typename Poses>
void save_poses(const SolverState& s, const Group& group, Poses& out) {
  for (int b : group.bodies) out[static_cast<size_t>(b)] = s.bodies[static_cast<size_t>(b)].pose();
}
template <typename Poses>
void load_poses(SolverState& s, const Group& group, const Poses& in) {
  for (int b : group.bodies) s.bodies[static_cast<size_t>(b)].set_pose(in[static_cast<size_t>(b)]);
}

// The same for a group's bodies alone, in the group's order: a Newton or seed step's poses before
// it, kept by each thread for the group it runs (a buffer of the whole model's poses was 77 kB
// of the 400 four-bars' solve, on the command's heap at its peak).
template <typename Poses>
void save_group_poses(const SolverState& s, const Group& group, Poses& out) {
  out.resize(group.bodies.size());
  for (size_t i = 0; i < group.bodies.size(); ++i) {
    out[i] = s.bodies[static_cast<size_t>(group.bodies[i])].pose();
  }
}
template <typename Poses>
void load_group_poses(SolverState& s, const Group& group, const Poses& in) {
  for (size_t i = 0; i < group.bodies.size(); ++i) {
    s.bodies[static_cast<size_t>(group.bodies[i])].set_pose(in[i]);
  }
}

// Threads for a solve (SolveOptions::threads, or a default from the groups' work).
int thread_count(const SolveOptions& o, const std::vector<Group>& groups);

}  // namespace dispcon
