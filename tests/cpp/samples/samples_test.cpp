// The samples against analytic answers (errors below 1e-9 at tolerance 1e-10), loading the real
// files so that the samples themselves are validated.
#include "support/samples.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/parts/twist.hpp"
#include "dispcon/solve/diagnostics.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {
namespace {

using test_support::id;
using test_support::sample;

SolveOptions tight() {
  SolveOptions o;
  o.tolerance = 1e-10;
  return o;
}

double angle_z(const Model& m, const char* name) {
  const Vec3 x = m.body(id(m, name)).pose.q * Vec3::UnitX();
  return std::atan2(x.y(), x.x());
}

Pose turn_z(double t) {
  return Pose::from(Vec3::Zero(), Vec3(0, 0, t));
}

TEST(Samples, FourBarFollowsFreudensteinOverAFullCrankTurn) {
  Model m = sample("fourbar.dcl");
  ASSERT_TRUE(assemble(m, tight()).converged);
  const double a = 1, b = 3, c = 2.5, d = 3;
  auto rocker = [&](double t) {  // circle intersection, the branch above the line A-D
    const Vec3 A(a * std::cos(t), a * std::sin(t), 0), D(d, 0, 0);
    const double L = (D - A).norm();
    const double x = (b * b - c * c + L * L) / (2 * L), h = std::sqrt(b * b - x * x);
    const Vec3 u = (D - A) / L, v(-u.y(), u.x(), 0);
    const Vec3 B = A + x * u + h * v;
    return std::atan2(B.y(), B.x() - d);
  };
  const double t0 = angle_z(m, "crank");
  ASSERT_NEAR(angle_z(m, "rocker"), rocker(t0), 1e-9);
  Dragger drag(m, id(m, "crank"), tight());
  double worst = 0;
  for (int k = 1; k <= 72; ++k) {
    const double t = t0 + 2 * kPi * k / 72;
    ASSERT_TRUE(drag.move_to(turn_z(t)).converged) << "step " << k;
    worst = std::max(worst, std::abs(std::remainder(angle_z(m, "rocker") - rocker(t), 2 * kPi)));
  }
  EXPECT_LT(worst, 1e-9);
}

TEST(Samples, SliderCrankPistonPosition) {
  Model m = sample("slider-crank.dcl");
  ASSERT_TRUE(assemble(m, tight()).converged);
  const double r = 1, l = 3, e = 0.2;
  const double t0 = angle_z(m, "crank");
  Dragger drag(m, id(m, "crank"), tight());
  double worst = 0;
  for (int k = 0; k <= 72; ++k) {
    const double t = t0 + 2 * kPi * k / 72;
    ASSERT_TRUE(drag.move_to(turn_z(t)).converged) << "step " << k;
    const double expected = r * std::cos(t) + std::sqrt(l * l - std::pow(r * std::sin(t) - e, 2));
    const Vec3 piston = m.body(id(m, "piston")).pose.x;
    worst = std::max({worst, std::abs(piston.x() - expected), std::abs(piston.y() - e)});
  }
  EXPECT_LT(worst, 1e-9);
}

// Joint angle of a Bennett joint: about the joint's axis, from the previous link's x to this one's.
double joint_angle(const Model& m, const char* prev, const char* link) {
  const Pose& p = m.body(id(m, prev)).pose;
  const Pose& q = m.body(id(m, link)).pose;
  const Vec3 z = q.q * Vec3::UnitZ();
  return twist_angle(z, z, p.q * Vec3::UnitX(), q.q * Vec3::UnitX());
}

TEST(Samples, BennettLinkageClosureOverAFullTurn) {
  Model m = sample("bennett.dcl");
  ASSERT_TRUE(assemble(m, tight()).converged);
  const double alpha = kPi / 6, beta = kPi / 3;
  const double K = -std::sin((beta + alpha) / 2) / std::sin((beta - alpha) / 2);
  // Joint 2 turns link2 about the world axis Rx(30 deg) z through (1, 0, 0); drive it by sweeping.
  SweepOptions s;
  s.body = id(m, "link2");
  s.axis = Vec3(0, -std::sin(alpha), std::cos(alpha));
  s.from = 0;
  s.to = 2 * kPi;
  s.steps = 72;
  s.solve = tight();
  const SweepResult r = sweep(m, s);
  ASSERT_FALSE(r.locked) << r.message;
  ASSERT_EQ(r.samples.size(), 73u);
  double worst = 0;
  int checked = 0;
  for (const SweepSample& x : r.samples) {
    Model at = m;
    at.set_poses(x.poses);
    const double t2 = joint_angle(at, "world", "link2");  // joint 2: world -> link2
    const double t3 = joint_angle(at, "link2", "link3");  // joint 3: link2 -> link3
    const double product = std::tan(t2 / 2) * std::tan(t3 / 2);
    if (std::abs(std::tan(t2 / 2)) > 1e3 || std::abs(std::tan(t3 / 2)) > 1e3) continue;
    worst = std::max(worst, std::abs(product - K) / std::abs(K));
    ++checked;
  }
  EXPECT_GT(checked, 60);
  EXPECT_LT(worst, 1e-9);
}

TEST(Samples, PeaucellierOutputOnItsStraightLine) {
  Model m = sample("peaucellier.dcl");
  ASSERT_TRUE(assemble(m, tight()).converged);
  const double l = 2, s = 1.2, r = 1;
  SweepOptions sw;
  sw.body = id(m, "crank");
  sw.from = 0;  // from the assembled crank angle 1.0 down to -1.5 rad
  sw.to = -2.5;
  sw.steps = 50;
  sw.solve = tight();
  Model start = m;
  const SweepResult res = sweep(m, sw);
  ASSERT_FALSE(res.locked) << res.message;
  double worst_line = 0, worst_inverse = 0;
  for (const SweepSample& x : res.samples) {
    const Vec3 A = x.poses[static_cast<size_t>(id(m, "crank").value)].apply(Vec3(r, 0, 0));
    const Vec3 P = x.poses[static_cast<size_t>(id(m, "pb").value)].x;
    worst_line = std::max(worst_line, std::abs(P.x() - (l * l - s * s) / (2 * r)));
    worst_inverse = std::max(worst_inverse, std::abs(A.norm() * P.norm() / (l * l - s * s) - 1));
  }
  EXPECT_LT(worst_line, 1e-9);
  EXPECT_LT(worst_inverse, 1e-9);
  // The crank locks where |OA| = l - s: its angle is 2 acos((l - s) / (2 r)).
  sw.from = 0;
  sw.to = 2;
  const SweepResult lock = sweep(start, sw);
  ASSERT_TRUE(lock.locked);
  const double crank0 = angle_z(start, "crank");
  EXPECT_NEAR(crank0 + lock.lock_value, 2 * std::acos((l - s) / (2 * r)), 1e-6);
}

TEST(Samples, SarrusPlatformMovesOnAStraightLine) {
  Model m = sample("sarrus.dcl");
  ASSERT_TRUE(assemble(m, tight()).converged);
  const Vec3 start = m.body(id(m, "top")).pose.x;
  EXPECT_NEAR(start.x(), 0, 1e-9);
  EXPECT_NEAR(start.y(), 0, 1e-9);
  // Turn the first link of limb a: the platform may only rise or sink, without turning.
  SweepOptions s;
  s.body = id(m, "a1");
  s.axis = Vec3::UnitX();
  s.from = 0;
  s.to = 0.6;
  s.steps = 30;
  s.solve = tight();
  const SweepResult r = sweep(m, s);
  ASSERT_FALSE(r.locked) << r.message;
  double worst = 0, rise = 0;
  for (const SweepSample& x : r.samples) {
    const Pose& top = x.poses[static_cast<size_t>(id(m, "top").value)];
    worst = std::max(
        {worst, std::abs(top.x.x()), std::abs(top.x.y()), top.q.angularDistance(Quat::Identity())});
    rise = std::max(rise, std::abs(top.x.z() - start.z()));
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_GT(rise, 0.1);  // it did move
}

TEST(Samples, RobotArmReachesATargetAndStopsAtAJointLimit) {
  Model m = sample("robot-arm.dcl");
  ASSERT_TRUE(assemble(m, tight()).converged);
  const BodyId hand = id(m, "hand");
  Pose target = m.body(hand).pose;
  target.x = Vec3(1.6, 1.2, 0.3);
  const DragResult reach = drag(m, hand, target, 40, tight());
  ASSERT_TRUE(reach.converged) << reach.message;
  EXPECT_LT((m.body(hand).pose.x - target.x).norm(), 1e-10);
  // Beyond reach: the arm is nearly stretched (the elbow bends at least 0.2 rad); pulling the
  // hand further out cannot be done, so the drag stops, with the elbow's limit in contact.
  Model far = sample("robot-arm.dcl");
  ASSERT_TRUE(assemble(far, tight()).converged);
  Pose away = far.body(hand).pose;
  away.x = Vec3(3, 0.5, 0);
  const std::vector<Pose> before = far.poses();
  const DragResult stop = drag(far, hand, away, 40, tight());
  EXPECT_FALSE(stop.converged);
  ASSERT_FALSE(stop.steps.empty());
  const std::vector<ConstraintReport>& failed = stop.steps.back().constraints;
  EXPECT_TRUE(failed[2].at_limit) << stop.message;  // the elbow, as straight as it may be
  EXPECT_FALSE(failed[1].at_limit);
  for (size_t i = 0; i < before.size(); ++i) EXPECT_EQ(far.poses()[i].x, before[i].x);
  // Joint limits hold at every pose the arm was left at.
  for (const ConstraintReport& r : measure(far, far.poses(), tight())) EXPECT_LT(r.residual, 1e-9);
}

TEST(Samples, MonocyclePedalsInFewIterationsPerStep) {
  Model m = sample("monocycle.dcl");
  ASSERT_TRUE(assemble(m).converged);
  const BodyId wheel = id(m, "wheel");
  const Pose w = m.body(wheel).pose;
  const Vec3 axle = w.q * Vec3::UnitX();
  Dragger pedal(m, wheel);
  std::vector<int> iterations;
  for (int k = 1; k <= 628; ++k) {  // two turns in 0.01 rad steps
    Pose p = w;
    p.q = quat_from_rotation_vector(axle * (0.01 * k)) * w.q;
    const SolveResult r = pedal.move_to(p);
    ASSERT_TRUE(r.converged) << "step " << k << ": " << r.message;
    iterations.push_back(r.iterations);
  }
  std::sort(iterations.begin(), iterations.end());
  const int median = iterations[iterations.size() / 2];
  const int p90 = iterations[iterations.size() * 9 / 10];
  RecordProperty("median_iterations", median);
  RecordProperty("worst_iterations", iterations.back());
  EXPECT_LT(median, 6);  // the seed: "fewer than six iterations per frame most of the time"
  EXPECT_LT(p90, 6);
  EXPECT_LE(iterations.back(), 20);
}

}  // namespace
}  // namespace dispcon
