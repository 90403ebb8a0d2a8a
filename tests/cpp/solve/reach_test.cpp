// Drag targets out of reach: recognised within a few dozen iterations, the linkage stretched as
// near as it can, and the step reporting the distance left (analytic answers).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dispcon/solve/solver.hpp"

namespace dispcon {
namespace {

// A chain of bars pinned end to end, the first to the world at the origin: bar i's local x axis
// runs from its start (its origin, pinned to the last bar's end) to its end at `lengths[i]`.
// Bar i lies at angle angles[i] (radians, absolute, in the xy plane). A hand (a body at the last
// bar's end, pinned there) is added when `hand` is set.
struct Chain {
  Model m;
  std::vector<BodyId> bars;
  BodyId hand{-1};
  Chain(const std::vector<double>& lengths, const std::vector<double>& angles, bool with_hand) {
    Vec3 at = Vec3::Zero();
    BodyId last = Model::kWorld;
    double last_length = 0;
    for (size_t i = 0; i < lengths.size(); ++i) {
      Body b;
      b.name = "bar" + std::to_string(i + 1);
      b.pose = Pose::from(at, Vec3(0, 0, angles[i]));
      b.center = Vec3(lengths[i] / 2, 0, 0);
      const BodyId id = m.add_body(b);
      Joint j;
      j.body1 = last;
      j.body2 = id;
      j.has_hinge = true;
      j.p1 = last == Model::kWorld ? Vec3::Zero() : Vec3(last_length, 0, 0);
      m.add_joint(j);
      at += lengths[i] * Vec3(std::cos(angles[i]), std::sin(angles[i]), 0);
      bars.push_back(id);
      last = id;
      last_length = lengths[i];
    }
    if (with_hand) {
      Body b;
      b.name = "hand";
      b.pose = Pose::from(at, Vec3::Zero());
      hand = m.add_body(b);
      Joint j;
      j.body1 = last;
      j.body2 = hand;
      j.has_hinge = true;
      j.p1 = Vec3(last_length, 0, 0);
      m.add_joint(j);
    }
  }
};

// Every joint holds at the model's poses.
void expect_joints_hold(const Model& m, double tolerance) {
  SolveOptions o;
  o.tolerance = tolerance;
  for (const ConstraintReport& c : measure(m, m.poses(), o)) {
    EXPECT_TRUE(c.satisfied) << "joint " << c.joint.value << " residual " << c.residual;
  }
}

// A 2-link arm (links 2 and 1.5, a hand pinned at its tip) whose hand is dragged to (3, 2.5),
// 3.905 from the shoulder: out of reach by |t| - (l1 + l2).
TEST(Reach, ArmOutOfReachIsToldWithTheDistanceLeft) {
  Chain arm({2.0, 1.5}, {0.3, 1.2}, true);
  ASSERT_TRUE(assemble(arm.m).converged);
  const std::vector<Pose> before = arm.m.poses();
  Dragger drag(arm.m, arm.hand);
  const Vec3 t(3, 2.5, 0);
  const SolveResult r = drag.move_to(Pose::from(t, Vec3::Zero()));
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, SolveStatus::OutOfReach);
  EXPECT_LE(r.iterations, 40);
  EXPECT_EQ(r.held.value, arm.hand.value);
  EXPECT_NEAR(r.distance_left, t.norm() - 3.5, 1e-12);
  EXPECT_NEAR(r.distance_left, 0.405125, 1e-6);
  EXPECT_NE(r.message.find("'hand'"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("out of reach"), std::string::npos) << r.message;
  EXPECT_FALSE(r.violated().empty());
  // A failed step leaves the model as it was, joints holding.
  for (size_t k = 0; k < before.size(); ++k) {
    EXPECT_EQ(arm.m.poses()[k].x, before[k].x);
    EXPECT_EQ(arm.m.poses()[k].q.coeffs(), before[k].q.coeffs());
  }
  expect_joints_hold(arm.m, 1e-9);
  // Within reach again, the drag goes on from where it was.
  const SolveResult back = drag.move_to(Pose::from(Vec3(2, 2, 0), Vec3::Zero()));
  EXPECT_TRUE(back.converged) << back.message;
}

// Near full stretch (3.49 of 3.5 from the shoulder) the step is reachable and converges.
TEST(Reach, ArmNearFullStretchStillConverges) {
  Chain arm({2.0, 1.5}, {0.3, 1.2}, true);
  ASSERT_TRUE(assemble(arm.m).converged);
  Dragger drag(arm.m, arm.hand);
  const Vec3 t = 3.49 * Vec3(std::cos(0.7), std::sin(0.7), 0);
  const SolveResult r = drag.move_to(Pose::from(t, Vec3::Zero()));
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LE(r.max_residual, 1e-9);
  EXPECT_LT((arm.m.body(arm.hand).pose.x - t).norm(), 1e-12);
  expect_joints_hold(arm.m, 1e-9);
  // The elbow is where the triangle of sides 2, 1.5, 3.49 puts it.
  const double elbow = (arm.m.body(arm.bars[1]).pose.x).norm();
  EXPECT_NEAR(elbow, 2.0, 1e-9);
  EXPECT_NEAR((t - arm.m.body(arm.bars[1]).pose.x).norm(), 1.5, 1e-9);
}

// The end of a gently curved 1,000-link chain (links turned by 0.02 sin(0.05 i) rad) dragged
// to x = 999.2 in 5 steps (docs/performance.md): step 1 is within reach (the end's start point
// is 999 links from the pinned one, its target 998.96 from it), step 2 is not.
TEST(Reach, ThousandLinkChainStopsAtTheFirstStepOutOfReach) {
  const int n = 1000;
  std::vector<double> lengths(n, 1.0), angles(n);
  for (int i = 0; i < n; ++i) angles[static_cast<size_t>(i)] = 0.02 * std::sin(0.05 * (i + 1));
  Chain c(lengths, angles, false);
  ASSERT_TRUE(assemble(c.m).converged);
  const BodyId end = c.bars.back();
  const Pose start = c.m.body(end).pose;
  const Pose goal{start.q, Vec3(999.2, start.x.y(), 0)};
  std::vector<std::vector<Pose>> steps;
  const DragResult d = drag(c.m, end, goal, 5, SolveOptions{}, &steps);
  EXPECT_FALSE(d.converged);
  ASSERT_EQ(d.steps.size(), 2u) << d.message;
  EXPECT_TRUE(d.steps[0].converged) << d.steps[0].message;
  EXPECT_LE(d.steps[0].max_residual, 1e-9);
  EXPECT_EQ(d.failed_step, 1);
  const SolveResult& out = d.steps[1];
  EXPECT_EQ(out.status, SolveStatus::OutOfReach);
  EXPECT_LE(out.iterations, 40);
  const Vec3 step2 = start.x + 0.4 * (goal.x - start.x);
  EXPECT_NEAR(out.distance_left, step2.norm() - (n - 1), 1e-9);
  EXPECT_NE(d.message.find("step 2 of 5 failed"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("'bar1000'"), std::string::npos) << d.message;
  // Left at step 1, joints holding.
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(c.m.body(end).pose.x, steps[0][static_cast<size_t>(end.value)].x);
  expect_joints_hold(c.m, 1e-9);
}

}  // namespace
}  // namespace dispcon
