// The constraint-processing loop: combining (seed 3.2, Fig. 2), stopping and reporting, dragging,
// time-varying constraints, and "a failed solve leaves the model as it was".
#include "dispcon/solve/solver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dispcon/solve/counted.hpp"

namespace dispcon {
namespace {

// Fig. 2: S0 tied by three point-to-point constraints (G0 to each Gi) to S1, S2, S3, which sit at
// the same place; S0 has half their mass.
Model star() {
  Model m;
  auto body = [&](const std::string& name, const Vec3& at, double mass) {
    Body b;
    b.name = name;
    b.pose.x = at;
    b.mass = mass;
    b.inertia = Mat3::Identity() * mass * 0.1;
    return m.add_body(b);
  };
  const BodyId s0 = body("s0", Vec3(0, 0, 0), 0.5);
  for (const char* name : {"s1", "s2", "s3"}) {
    Joint j;
    j.body1 = s0;
    j.body2 = body(name, Vec3(1, 0.5, -0.25), 1.0);
    j.has_hinge = true;
    m.add_joint(j);
  }
  return m;
}

TEST(Combining, StarConvergesWithSeedWeights) {
  Model m = star();
  SolveOptions o;
  o.newton_polish = false;
  o.tolerance = 1e-12;
  const SolveResult r = assemble(m, o);
  ASSERT_TRUE(r.converged) << r.message;
  // The gap shrinks by 2/9 each iteration (1 - 1/9 - 2/3): about 19 iterations to 1e-12.
  EXPECT_LT(r.iterations, 30);
  // Momentum: the centre of mass does not move (internal corrections only).
  Vec3 com = Vec3::Zero();
  double total = 0;
  for (int i = 1; i < m.body_count(); ++i) {
    com += *m.body(BodyId{i}).mass * m.body(BodyId{i}).pose.x;
    total += *m.body(BodyId{i}).mass;
  }
  const Vec3 start_com = (3 * Vec3(1, 0.5, -0.25)) / 3.5;
  EXPECT_LT((com / total - start_com).norm(), 1e-12);
}

TEST(Combining, StarDivergesWithPlainSum) {
  Model m = star();
  const std::vector<Pose> before = m.poses();
  SolveOptions o;
  o.newton_polish = false;
  o.seed_weights = false;
  o.record_history = true;
  o.max_iterations = 20;
  const SolveResult r = assemble(m, o);
  EXPECT_FALSE(r.converged);
  ASSERT_EQ(r.history.size(), 20u);
  // Summing: S0 moves 3 * 2/3 of the gap, each Si 1/3 of it back: the gap becomes -4/3 of itself.
  const double gap0 = (before[2].x - before[1].x).norm();
  for (size_t k = 0; k < r.history.size(); ++k) {
    EXPECT_NEAR(r.history[k], gap0 * std::pow(4.0 / 3.0, static_cast<double>(k + 1)),
                1e-9 * r.history[k]);
  }
  // A failed solve leaves the model as it was.
  for (int i = 0; i < m.body_count(); ++i) {
    EXPECT_EQ(m.body(BodyId{i}).pose.x, before[static_cast<size_t>(i)].x);
  }
}

TEST(Combining, StarShrinksByTwoNinthsWithSeedWeights) {
  Model m = star();
  const double gap0 = (m.body(BodyId{2}).pose.x - m.body(BodyId{1}).pose.x).norm();
  SolveOptions o;
  o.newton_polish = false;
  o.record_history = true;
  o.max_iterations = 8;
  const SolveResult r = assemble(m, o);
  ASSERT_EQ(r.history.size(), 8u);
  for (size_t k = 0; k < r.history.size(); ++k) {
    EXPECT_NEAR(r.history[k], gap0 * std::pow(2.0 / 9.0, static_cast<double>(k + 1)), 1e-9 * gap0);
  }
}

// A planar crank-rocker built of revolute joints (hinge + `angle z z max 0`): in 3D it has three
// redundant equations, which the solve must take in its stride.
struct FourBar {
  double a = 1.0, b = 3.0, c = 2.5, d = 3.0;  // crank, coupler, rocker, ground
  Model m;
  BodyId crank, coupler, rocker;

  FourBar() {
    auto body = [&](const std::string& name, const Vec3& at, double angle) {
      Body bd;
      bd.name = name;
      bd.pose = Pose::from(at, Vec3(0, 0, angle));
      return m.add_body(bd);
    };
    crank = body("crank", Vec3(0.1, -0.1, 0.05), 0.4);
    coupler = body("coupler", Vec3(1.2, 0.6, -0.1), 0.2);
    rocker = body("rocker", Vec3(2.9, 0.2, 0.1), 1.9);
    revolute(Model::kWorld, crank, Vec3(0, 0, 0), Vec3(0, 0, 0));
    revolute(crank, coupler, Vec3(a, 0, 0), Vec3(0, 0, 0));
    revolute(coupler, rocker, Vec3(b, 0, 0), Vec3(c, 0, 0));
    revolute(Model::kWorld, rocker, Vec3(d, 0, 0), Vec3(0, 0, 0));
  }
  void revolute(BodyId b1, BodyId b2, const Vec3& p1, const Vec3& p2) {
    Joint j;
    j.body1 = b1;
    j.body2 = b2;
    j.has_hinge = true;
    j.p1 = p1;
    j.p2 = p2;
    j.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
    m.add_joint(j);
  }
  double angle_of(BodyId id) const {
    const Vec3 x = m.body(id).pose.q * Vec3::UnitX();
    return std::atan2(x.y(), x.x());
  }
  // Rocker angle for crank angle t on the branch where the coupler-rocker pin is above the line
  // from the crank tip to the ground pivot (Freudenstein's closure, by circle intersection).
  double rocker_angle(double t) const {
    const Vec3 A(a * std::cos(t), a * std::sin(t), 0);
    const Vec3 D(d, 0, 0);
    const double L = (D - A).norm();
    const double x = (b * b - c * c + L * L) / (2 * L);
    const double h = std::sqrt(b * b - x * x);
    const Vec3 u = (D - A) / L;
    const Vec3 v(-u.y(), u.x(), 0);
    const Vec3 B = A + x * u + h * v;
    return std::atan2(B.y() - D.y(), B.x() - D.x());
  }
};

// Sixty four-bars side by side (along z), each from its own rough start: sixty groups of bodies,
// enough for a solve to share them among threads.
Model many_fourbars(int n) {
  Model m;
  FourBar one;
  for (int k = 0; k < n; ++k) {
    const int base = m.body_count() - 1;
    for (int b = 1; b < one.m.body_count(); ++b) {
      Body body = one.m.body(BodyId{b});
      body.name += std::to_string(k);
      body.pose.x += Vec3(0.01 * std::sin(k), 0.02 * std::cos(k), 5.0 * k);
      body.pose.q = quat_from_rotation_vector(Vec3(0, 0, 0.05 * std::sin(3.0 * k))) * body.pose.q;
      m.add_body(body);
    }
    for (int c = 0; c < one.m.joint_count(); ++c) {
      Joint j = one.m.joint(JointId{c});
      for (BodyId* id : {&j.body1, &j.body2}) {
        if (*id == Model::kWorld) {
          (id == &j.body1 ? j.p1 : j.p2) += Vec3(0, 0, 5.0 * k);
        } else {
          *id = BodyId{id->value + base};
        }
      }
      m.add_joint(j);
    }
  }
  return m;
}

TEST(Threads, GroupsSolveTheSameOnAnyNumberOfThreads) {
  const Model start = many_fourbars(60);
  std::vector<SolveResult> results;
  std::vector<std::vector<Pose>> poses;
  for (int threads : {1, 2, 3}) {
    Model m = start;
    SolveOptions o;
    o.threads = threads;
    o.record_history = true;
    results.push_back(assemble(m, o));
    ASSERT_TRUE(results.back().converged) << results.back().message;
    poses.push_back(m.poses());
  }
  for (size_t t = 1; t < results.size(); ++t) {
    EXPECT_EQ(results[t].iterations, results[0].iterations);
    EXPECT_EQ(results[t].history, results[0].history);
    for (size_t b = 0; b < poses[0].size(); ++b) {
      EXPECT_EQ(poses[t][b].x, poses[0][b].x) << "body " << b;
      EXPECT_EQ(poses[t][b].q.coeffs(), poses[0][b].q.coeffs()) << "body " << b;
    }
  }
  // And each four-bar closes as Freudenstein says.
  FourBar fb;
  Model m = start;
  ASSERT_TRUE(assemble(m).converged);
  for (int k = 0; k < 60; ++k) {
    auto angle = [&](const std::string& name) {
      const Vec3 x = m.body(*m.find(name + std::to_string(k))).pose.q * Vec3::UnitX();
      return std::atan2(x.y(), x.x());
    };
    const double err = std::remainder(angle("rocker") - fb.rocker_angle(angle("crank")), 2 * kPi);
    EXPECT_LT(std::abs(err), 1e-8) << "four-bar " << k;
  }
}

TEST(Drag, FourBarFollowsFreudensteinOverAFullTurn) {
  FourBar fb;
  SolveOptions o;
  o.tolerance = 1e-10;
  const SolveResult r = assemble(fb.m, o);
  ASSERT_TRUE(r.converged) << r.message;
  const double t0 = fb.angle_of(fb.crank);
  ASSERT_NEAR(fb.angle_of(fb.rocker), fb.rocker_angle(t0), 1e-9) << "assembled on the other branch";
  const int steps = 72;
  for (int k = 1; k <= steps; ++k) {
    const double t = t0 + 2 * kPi * k / steps;
    const DragResult d = drag(fb.m, fb.crank, Pose::from(Vec3::Zero(), Vec3(0, 0, t)), 1, o);
    ASSERT_TRUE(d.converged) << "step " << k << ": " << d.message;
    const double err = std::remainder(fb.angle_of(fb.rocker) - fb.rocker_angle(t), 2 * kPi);
    EXPECT_LT(std::abs(err), 1e-9) << "step " << k;
  }
}

TEST(Drag, HeldBodyStaysAtEachStepTarget) {
  FourBar fb;
  ASSERT_TRUE(assemble(fb.m).converged);
  std::vector<std::vector<Pose>> steps;
  const Pose target = Pose::from(Vec3::Zero(), Vec3(0, 0, fb.angle_of(fb.crank) + 0.5));
  const DragResult d = drag(fb.m, fb.crank, target, 10, SolveOptions{}, &steps);
  ASSERT_TRUE(d.converged) << d.message;
  ASSERT_EQ(steps.size(), 10u);
  EXPECT_LT((fb.m.body(fb.crank).pose.q.coeffs() - target.q.coeffs()).norm(), 1e-12);
  // Continuity: the rocker moves little between steps (no jump to the other branch).
  for (size_t k = 1; k < steps.size(); ++k) {
    const double turn = steps[k][3].q.angularDistance(steps[k - 1][3].q);
    EXPECT_LT(turn, 0.1) << "step " << k;
  }
}

// The one line a person reads counts in words: "1 step", "1 iteration", never "1 steps".
TEST(Drag, MessageSaysOneStepInTheSingular) {
  FourBar fb;
  ASSERT_TRUE(assemble(fb.m).converged);
  const Pose target = Pose::from(Vec3::Zero(), Vec3(0, 0, fb.angle_of(fb.crank) + 0.1));
  const DragResult d = drag(fb.m, fb.crank, target, 1, SolveOptions{});
  ASSERT_TRUE(d.converged) << d.message;
  ASSERT_GE(d.iterations, 2);
  EXPECT_EQ(d.message, "dragged '" + fb.m.body(fb.crank).name + "' in 1 step, " +
                           std::to_string(d.iterations) + " iterations");
  const DragResult two = drag(fb.m, fb.crank, target, 2, SolveOptions{});
  ASSERT_TRUE(two.converged) << two.message;
  EXPECT_EQ(two.message, "dragged '" + fb.m.body(fb.crank).name + "' in 2 steps, 0 iterations");
  const SolveResult again = assemble(fb.m);
  ASSERT_TRUE(again.converged);
  EXPECT_EQ(again.message.rfind("converged in 0 iterations (", 0), 0u) << again.message;
  EXPECT_EQ(counted(1, "iteration"), "1 iteration");
  EXPECT_EQ(counted(0, "frame"), "0 frames");
  EXPECT_EQ(counted(31, "step"), "31 steps");
}

TEST(Drag, UnreachableTargetStopsAndKeepsLastGoodStep) {
  FourBar fb;
  ASSERT_TRUE(assemble(fb.m).converged);
  // Pull the crank's pivot off the ground pivot: no solution.
  const Pose target = Pose::from(Vec3(0.5, 0, 0), Vec3(0, 0, fb.angle_of(fb.crank)));
  SolveOptions o;
  o.max_iterations = 200;
  const DragResult d = drag(fb.m, fb.crank, target, 5, o);
  EXPECT_FALSE(d.converged);
  EXPECT_EQ(d.failed_step, 0);
  ASSERT_FALSE(d.steps.empty());
  const std::vector<JointId> bad = d.steps.back().violated();
  ASSERT_FALSE(bad.empty());
  EXPECT_EQ(bad.front().value, 0) << d.message;  // the crank's pivot joint is the violated one
  EXPECT_LT(fb.m.body(fb.crank).pose.x.norm(), 1e-9);  // left at the last good step
}

TEST(Stopping, OverConstrainedNamesTheJointsAndKeepsTheModel) {
  Model m;
  Body b;
  b.name = "bar";
  const BodyId bar = m.add_body(b);
  Joint j1;
  j1.body2 = bar;
  j1.has_hinge = true;
  j1.p1 = Vec3(0, 0, 0);
  j1.line = 3;
  Joint j2 = j1;
  j2.p1 = Vec3(1, 0, 0);  // the same point of the bar pinned at two places of the world
  j2.line = 7;
  m.add_joint(j1);
  m.add_joint(j2);
  const std::vector<Pose> before = m.poses();
  SolveOptions o;
  o.max_iterations = 300;
  const SolveResult r = assemble(m, o);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.status, SolveStatus::IterationLimit);
  EXPECT_EQ(r.violated().size(), 2u);
  EXPECT_NE(r.message.find("line 3"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("line 7"), std::string::npos) << r.message;
  EXPECT_NEAR(r.max_residual, 0.5, 1e-6);  // the best it can do: halfway
  EXPECT_EQ(m.body(bar).pose.x, before[1].x);
}

TEST(Time, ConstraintActiveOnlyInItsInterval) {
  Model m;
  Body b;
  b.name = "ball";
  b.pose.x = Vec3(2, 0, 0);
  const BodyId ball = m.add_body(b);
  Joint j;
  j.body2 = ball;
  j.has_hinge = true;
  j.t0 = 1.0;
  j.t1 = 2.0;
  m.add_joint(j);
  SolveOptions o;
  o.time = 0.5;
  SolveResult r = assemble(m, o);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_FALSE(r.constraints[0].active);
  EXPECT_EQ(m.body(ball).pose.x, Vec3(2, 0, 0));
  o.time = 1.5;
  r = assemble(m, o);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(m.body(ball).pose.x.norm(), 1e-9);
}

TEST(Schemes, GaussSeidelAndJacobiReachTheSameFourBar) {
  for (Scheme scheme : {Scheme::Jacobi, Scheme::GaussSeidel}) {
    FourBar fb;
    SolveOptions o;
    o.scheme = scheme;
    o.tolerance = 1e-10;
    const SolveResult r = assemble(fb.m, o);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_NEAR(fb.angle_of(fb.rocker), fb.rocker_angle(fb.angle_of(fb.crank)), 1e-9);
  }
}

TEST(Drag, DraggerReusesItsSessionAndMatchesFreshSolves) {
  FourBar live, fresh;
  ASSERT_TRUE(assemble(live.m).converged);
  ASSERT_TRUE(assemble(fresh.m).converged);
  Dragger dragger(live.m, live.crank);
  const double t0 = live.angle_of(live.crank);
  for (int k = 1; k <= 20; ++k) {
    const Pose target = Pose::from(Vec3::Zero(), Vec3(0, 0, t0 + 0.05 * k));
    const SolveResult r = dragger.move_to(target);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_LE(r.iterations, 4) << "step " << k;
    ASSERT_TRUE(drag(fresh.m, fresh.crank, target, 1).converged);
    EXPECT_NEAR(live.angle_of(live.rocker), fresh.angle_of(fresh.rocker), 1e-9);
    EXPECT_NEAR(live.angle_of(live.rocker), live.rocker_angle(t0 + 0.05 * k), 1e-8);
  }
}

TEST(Drag, DraggerRefusesFixedAndUnknownBodies) {
  FourBar fb;
  EXPECT_THROW(Dragger(fb.m, Model::kWorld), std::invalid_argument);
  EXPECT_THROW(Dragger(fb.m, BodyId{42}), std::invalid_argument);
  fb.m.set_fixed(fb.coupler, true);
  EXPECT_THROW(Dragger(fb.m, fb.coupler), std::invalid_argument);
}

TEST(Drag, FailedMoveLeavesTheModelUnchanged) {
  FourBar fb;
  ASSERT_TRUE(assemble(fb.m).converged);
  const std::vector<Pose> before = fb.m.poses();
  SolveOptions o;
  o.max_iterations = 100;
  Dragger dragger(fb.m, fb.rocker, o);
  // The rocker's pivot pulled 10 units away from the ground pivot: impossible.
  const SolveResult r = dragger.move_to(Pose::from(Vec3(10, 0, 0), Vec3::Zero()));
  EXPECT_FALSE(r.converged);
  for (int i = 0; i < fb.m.body_count(); ++i) {
    EXPECT_EQ(fb.m.body(BodyId{i}).pose.x, before[static_cast<size_t>(i)].x);
  }
}

}  // namespace
}  // namespace dispcon
