#include "dispcon/solve/seed_iteration.hpp"

namespace dispcon {

namespace {

Vec3 clamp_norm(const Vec3& v, double limit) {
  const double n = v.norm();
  return n > limit ? Vec3(v * (limit / n)) : v;
}

}  // namespace

// One iteration of seed 3.2: propose, weight by 1/max(n_i, n_j), combine rotations, apply;
// then the same for translations (from the rotated positions, eq. 19, or from the same positions
// as the rotations, eq. 15).
void jacobi_iteration(SolverState& s, const Group& group, const SolveOptions& o) {
  std::vector<Vec3>& turn = s.proposed_turn;
  std::vector<Vec3>& move = s.proposed_move;
  for (int b : group.bodies) {
    turn[static_cast<size_t>(b)].setZero();
    move[static_cast<size_t>(b)].setZero();
  }
  // Only the group's own (movable) bodies are written: groups may run on several threads, and
  // the bodies that cannot move (the world, fixed parts) are shared between them.
  Vec3 d1, d2;
  auto add = [&](std::vector<Vec3>& sum, int b, const Vec3& d, double w) {
    if (s.bodies[static_cast<size_t>(b)].movable) sum[static_cast<size_t>(b)] += w * d;
  };
  auto add_translations = [&](const JointState& js) {
    s.propose_translations(js, d1, d2);
    add(move, js.b1, d1, js.w);
    add(move, js.b2, d2, js.w);
  };
  for (int c : group.joints) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    s.propose_rotations(js, d1, d2);
    add(turn, js.b1, d1, js.w);
    add(turn, js.b2, d2, js.w);
    if (!o.translate_after_rotate) add_translations(js);
  }
  for (int b : group.bodies) {
    s.bodies[static_cast<size_t>(b)].displace(
        clamp_norm(turn[static_cast<size_t>(b)], o.max_rotation_step), Vec3::Zero());
  }
  if (o.translate_after_rotate) {
    for (int c : group.joints) add_translations(s.joints[static_cast<size_t>(c)]);
  }
  for (int b : group.bodies) {
    s.bodies[static_cast<size_t>(b)].displace(Vec3::Zero(), move[static_cast<size_t>(b)]);
  }
}

// Gauss-Seidel ordering: each joint's correction is applied at once, in model order.
void gauss_seidel_iteration(SolverState& s, const Group& group, const SolveOptions& o) {
  Vec3 d1, d2;
  const double w = o.relaxation;
  for (int c : group.joints) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    BodyState& b1 = s.bodies[static_cast<size_t>(js.b1)];
    BodyState& b2 = s.bodies[static_cast<size_t>(js.b2)];
    s.propose_rotations(js, d1, d2);
    if (b1.movable) b1.displace(clamp_norm(w * d1, o.max_rotation_step), Vec3::Zero());
    if (b2.movable) b2.displace(clamp_norm(w * d2, o.max_rotation_step), Vec3::Zero());
    s.propose_translations(js, d1, d2);
    if (b1.movable) b1.displace(Vec3::Zero(), w * d1);
    if (b2.movable) b2.displace(Vec3::Zero(), w * d2);
  }
}

}  // namespace dispcon
