#include "dispcon/solve/group.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <thread>
#include <utility>

namespace dispcon {

std::vector<Group> find_groups(const SolverState& s) {
  const int n = static_cast<int>(s.bodies.size());
  std::vector<int> parent(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) parent[static_cast<size_t>(i)] = i;
  auto find = [&](int i) {
    while (parent[static_cast<size_t>(i)] != i) {
      parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
      i = parent[static_cast<size_t>(i)];
    }
    return i;
  };
  for (const JointState& js : s.joints) {
    if (js.active && s.bodies[static_cast<size_t>(js.b1)].movable &&
        s.bodies[static_cast<size_t>(js.b2)].movable) {
      parent[static_cast<size_t>(find(js.b1))] = find(js.b2);
    }
  }
  // Each movable body's group (numbered in the order of their first bodies) and each active
  // joint's, counted first so that every list is allocated once at its size: grown entry by
  // entry, the 400 four-bars' lists were some 2,000 allocations and copies (1 % of the command).
  std::vector<int> index(static_cast<size_t>(n), -1);
  std::vector<int> body_group(static_cast<size_t>(n), -1);
  std::vector<int> joint_group(s.joints.size(), -1);
  std::vector<std::pair<int, int>> counts;  // each group's bodies and joints
  for (int i = 0; i < n; ++i) {
    if (!s.bodies[static_cast<size_t>(i)].movable) continue;
    int& k = index[static_cast<size_t>(find(i))];
    if (k < 0) k = static_cast<int>(counts.size()), counts.emplace_back(0, 0);
    body_group[static_cast<size_t>(i)] = k;
    ++counts[static_cast<size_t>(k)].first;
  }
  for (size_t c = 0; c < s.joints.size(); ++c) {
    const JointState& js = s.joints[c];
    if (!js.active) continue;
    const int b = s.bodies[static_cast<size_t>(js.b1)].movable ? js.b1 : js.b2;
    if (!s.bodies[static_cast<size_t>(b)].movable) continue;
    const int k = body_group[static_cast<size_t>(b)];
    joint_group[c] = k;
    ++counts[static_cast<size_t>(k)].second;
  }
  std::vector<Group> out(counts.size());
  for (size_t k = 0; k < counts.size(); ++k) {
    out[k].bodies.reserve(static_cast<size_t>(counts[k].first));
    out[k].joints.reserve(static_cast<size_t>(counts[k].second));
  }
  for (int i = 0; i < n; ++i) {
    const int k = body_group[static_cast<size_t>(i)];
    if (k >= 0) out[static_cast<size_t>(k)].bodies.push_back(i);
  }
  for (size_t c = 0; c < s.joints.size(); ++c) {
    const int k = joint_group[c];
    if (k >= 0) out[static_cast<size_t>(k)].joints.push_back(static_cast<int>(c));
  }
  return out;
}

double max_residual(const SolverState& s, const std::vector<int>& joints,
                    std::vector<double>& store) {
  double r = 0;
  for (int c : joints) {
    const double rc = s.residual(s.joints[static_cast<size_t>(c)]);
    store[static_cast<size_t>(c)] = rc;
    r = larger_residual(r, rc);
  }
  return r;
}

double group_size(const SolverState& s, const Group& group) {
  Eigen::AlignedBox3d box;
  for (int b : group.bodies) {
    box.extend(s.bodies[static_cast<size_t>(b)].x);
    box.extend(s.bodies[static_cast<size_t>(b)].G);
  }
  for (int c : group.joints) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    const BodyState& b1 = s.bodies[static_cast<size_t>(js.b1)];
    const BodyState& b2 = s.bodies[static_cast<size_t>(js.b2)];
    box.extend(b1.R * js.joint->p1 + b1.x);
    box.extend(b2.R * js.joint->p2 + b2.x);
    if (js.joint->guide) {
      for (const Vec3& q : js.joint->guide->points) box.extend(b1.R * q + b1.x);
    }
  }
  return box.isEmpty() ? 1e-6 : std::max(1e-6, box.diagonal().norm());
}

// Threads for a solve: SolveOptions::threads when given; by default every core, but only when
// there are several groups and some 4 ms of work between them (2,500 joints; the 400 four-bars'
// 1,200 joints take about 1.9 ms on one core): a second thread costs 0.2-0.6 ms of CPU on the
// development VM (its start and stack, and the groups' data moving to another core's caches:
// the same instructions, measured in the whole `dispcon assemble` process), and on a machine
// whose other core is busy it made the 400 four-bars' solve slower in wall time too (4.3-5.0 ms
// on one thread against 7.3-8.0 ms on two, at load 6 to 7). Below that, one thread. Starting
// threads for a drag step of a hundred parts cannot pay either (a closed chain held at one link
// splits in two groups: two threads made its step 4 times slower).
int thread_count(const SolveOptions& o, const std::vector<Group>& groups) {
  constexpr size_t kThreadJoints = 2500;
  if (o.threads == 1 || groups.size() < 2) return 1;
  size_t joints = 0;
  for (const Group& c : groups) joints += c.joints.size();
  if (o.threads <= 0 && joints < kThreadJoints) return 1;
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  const int wanted = o.threads > 1 ? o.threads : std::max(1, cores);
  return std::min(wanted, static_cast<int>(groups.size()));
}

}  // namespace dispcon
