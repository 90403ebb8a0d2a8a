// Drag targets out of reach: recognised within a few dozen iterations, the linkage stretched as
// near as it can, and the step reporting the distance left (analytic answers).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/parts/angle.hpp"
#include "dispcon/parts/twist.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {
namespace {

// A pin (point to point: free to turn every way) from body1's point p1 to body2's origin.
Joint pin(BodyId body1, BodyId body2, const Vec3& p1) {
  Joint j;
  j.body1 = body1;
  j.body2 = body2;
  j.has_hinge = true;
  j.p1 = p1;
  return j;
}

// A chain of bars pinned end to end, the first to the world at the origin: bar i's local x axis
// runs from its start (its origin, pinned to the last bar's end) to its end at `lengths[i]`.
// Bar i lies at angle angles[i] (radians, absolute, in the xy plane). A hand (a body at the last
// bar's end, pinned there) is added when `hand` is set.
struct Chain {
  Model m;
  std::vector<BodyId> bars;
  BodyId hand{-1};
  // n unit links, link i turned by 0.02 sin(0.05 i) rad: a gently curved chain, nearly
  // stretched (docs/performance.md's 1,000-link drag).
  static Chain gently_curved(int n) {
    std::vector<double> lengths(static_cast<size_t>(n), 1.0), angles(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) angles[static_cast<size_t>(i)] = 0.02 * std::sin(0.05 * (i + 1));
    return Chain(lengths, angles, false);
  }
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
      m.add_joint(pin(last, id, last == Model::kWorld ? Vec3::Zero() : Vec3(last_length, 0, 0)));
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
      m.add_joint(pin(last, hand, Vec3(last_length, 0, 0)));
    }
  }
};

// Every joint holds at the given poses (the model's when none are given).
void expect_joints_hold(const Model& m, double tolerance,
                        const std::vector<Pose>* poses = nullptr) {
  SolveOptions o;
  o.tolerance = tolerance;
  for (const ConstraintReport& c : measure(m, poses ? *poses : m.poses(), o)) {
    EXPECT_TRUE(c.satisfied) << "joint " << c.joint.value << " residual " << c.residual;
  }
}

void expect_unchanged(const Model& m, const std::vector<Pose>& before) {
  for (size_t k = 0; k < before.size(); ++k) {
    EXPECT_EQ(m.poses()[k].x, before[k].x) << k;
    EXPECT_EQ(m.poses()[k].q.coeffs(), before[k].q.coeffs()) << k;
  }
}

// A planar revolute (a hinge whose z axes stay parallel) from body1's point p1 to body2's origin.
Joint revolute(BodyId body1, BodyId body2, const Vec3& p1) {
  Joint j = pin(body1, body2, p1);
  j.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
  return j;
}

BodyId add_bar(Model& m, const std::string& name, const Vec3& at, double angle, double length) {
  Body b;
  b.name = name;
  b.pose = Pose::from(at, Vec3(0, 0, angle));
  b.center = Vec3(length / 2, 0, 0);
  return m.add_body(b);
}

double angle_of(const Pose& p) {
  const Vec3 x = p.q * Vec3::UnitX();
  return std::atan2(x.y(), x.x());
}

// A planar 2-link arm (upper arm 2, forearm 1.5, a hand pinned at the tip) whose elbow bends
// between 0.5 and 2 rad: the hand reaches from r(2) to r(0.5) from the shoulder,
// r(theta) = |l1 + l2 e^(i theta)|, though the links stretch to 3.5.
struct LimitedArm {
  static constexpr double l1 = 2, l2 = 1.5, bend_min = 0.5, bend_max = 2;
  Model m;
  BodyId upper, forearm, hand;
  LimitedArm() {
    upper = add_bar(m, "upper", Vec3::Zero(), 0.3, l1);
    const Vec3 elbow = l1 * Vec3(std::cos(0.3), std::sin(0.3), 0);
    forearm = add_bar(m, "forearm", elbow, 1.3, l2);
    Body h;
    h.name = "hand";
    h.pose = Pose::from(elbow + l2 * Vec3(std::cos(1.3), std::sin(1.3), 0), Vec3::Zero());
    hand = m.add_body(h);
    m.add_joint(revolute(Model::kWorld, upper, Vec3::Zero()));
    Joint e = revolute(upper, forearm, Vec3(l1, 0, 0));
    e.twist = TwistSpec{Vec3::UnitX(), Vec3::UnitX(), bend_min, bend_max};
    m.add_joint(e);
    m.add_joint(pin(forearm, hand, Vec3(l2, 0, 0)));
  }
  static double reach(double bend) {
    return std::sqrt(l1 * l1 + l2 * l2 + 2 * l1 * l2 * std::cos(bend));
  }
  // The upper arm's angle when the hand points along `direction` with the elbow bent by `bend`.
  static double shoulder(double direction, double bend) {
    return direction - std::atan2(l2 * std::sin(bend), l1 + l2 * std::cos(bend));
  }
};

// The arm's hand dragged toward `goal` in `steps` steps, beyond what its elbow's limit lets it
// reach (the links alone would): the first step out of reach stops within a few dozen iterations,
// out of reach, with the nearest pose (the elbow at its limit, the hand on the line to that
// step's target) and the distance left in closed form.
void expect_arm_stops_at_its_limit(const Vec3& goal, int steps) {
  LimitedArm arm;
  ASSERT_TRUE(assemble(arm.m).converged);
  const Vec3 start = arm.m.body(arm.hand).pose.x;
  std::vector<std::vector<Pose>> done;
  const DragResult d =
      drag(arm.m, arm.hand, Pose::from(goal, Vec3::Zero()), steps, SolveOptions{}, &done);
  ASSERT_FALSE(d.converged);
  ASSERT_GE(d.failed_step, 1) << d.message;
  const SolveResult& r = d.steps.back();
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_FALSE(r.converged);
  EXPECT_LE(r.iterations, 40);
  EXPECT_EQ(r.held.value, arm.hand.value);
  const double k = static_cast<double>(d.failed_step + 1) / steps;
  const Vec3 t = (1 - k) * start + k * goal;
  const double bend = t.norm() > LimitedArm::reach(LimitedArm::bend_min) ? LimitedArm::bend_min
                                                                         : LimitedArm::bend_max;
  const double reach = LimitedArm::reach(bend);
  EXPECT_NEAR(r.distance_left, std::abs(t.norm() - reach), 1e-9);
  EXPECT_NE(r.message.find("'hand'"), std::string::npos) << r.message;
  // The nearest pose: valid, the elbow at its limit, the hand on the line to the target (the
  // distance is of second order in an error of the pose there, so the pose is known to the root
  // of the distance's precision).
  ASSERT_EQ(r.poses.size(), arm.m.poses().size());
  expect_joints_hold(arm.m, 1e-9, &r.poses);
  const double direction = std::atan2(t.y(), t.x());
  const Pose& upper = r.poses[static_cast<size_t>(arm.upper.value)];
  const Pose& forearm = r.poses[static_cast<size_t>(arm.forearm.value)];
  EXPECT_NEAR(std::remainder(angle_of(forearm) - angle_of(upper) - bend, 2 * kPi), 0, 1e-9);
  EXPECT_NEAR(std::remainder(angle_of(upper) - LimitedArm::shoulder(direction, bend), 2 * kPi), 0,
              1e-4);
  EXPECT_LT((r.poses[static_cast<size_t>(arm.hand.value)].x - reach * t.normalized()).norm(), 1e-4);
  // The step names the hand's joint, which holding the hand at its target leaves open, and the
  // elbow at its limit.
  ASSERT_EQ(r.constraints.size(), 3u);
  EXPECT_FALSE(r.constraints[2].satisfied);
  EXPECT_TRUE(r.constraints[1].at_limit);
  // A step that failed leaves the model at the last good step.
  ASSERT_EQ(done.size(), static_cast<size_t>(d.failed_step));
  expect_unchanged(arm.m, done.back());
  expect_joints_hold(arm.m, 1e-9);
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
  EXPECT_EQ(r.iterations, 0);  // the stretched arm breaks no joint: no pull is needed
  EXPECT_EQ(r.held.value, arm.hand.value);
  EXPECT_NEAR(r.distance_left, t.norm() - 3.5, 1e-12);
  EXPECT_NEAR(r.distance_left, 0.405125, 1e-6);
  EXPECT_NE(r.message.find("'hand'"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("out of reach"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("nearest pose"), std::string::npos) << r.message;
  EXPECT_FALSE(r.violated().empty());
  // The nearest pose: the arm stretched toward the target, the elbow 2 and the hand 3.5 along it,
  // every joint holding.
  const Vec3 u = t.normalized();
  expect_joints_hold(arm.m, 1e-12, &r.poses);
  EXPECT_LT((r.poses[static_cast<size_t>(arm.bars[1].value)].x - 2 * u).norm(), 1e-12);
  EXPECT_LT((r.poses[static_cast<size_t>(arm.hand.value)].x - 3.5 * u).norm(), 1e-12);
  for (BodyId bar : arm.bars) {
    EXPECT_LT((r.poses[static_cast<size_t>(bar.value)].q * Vec3::UnitX() - u).norm(), 1e-12);
  }
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
  Chain c = Chain::gently_curved(n);
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
  // The nearest pose: the chain stretched straight toward step 2's target, every joint holding
  // (the held link, dragged by its start point and free to turn, keeps its direction).
  expect_joints_hold(c.m, 1e-9, &out.poses);
  const Vec3 u = step2.normalized();
  for (int i = 0; i < n; ++i) {
    const Pose& bar = out.poses[static_cast<size_t>(c.bars[static_cast<size_t>(i)].value)];
    EXPECT_LT((bar.x - i * u).norm(), 1e-9) << i;
    if (i < n - 1) EXPECT_LT((bar.q * Vec3::UnitX() - u).norm(), 1e-12) << i;
  }
  EXPECT_EQ(out.poses[static_cast<size_t>(end.value)].q.coeffs(),
            steps[0][static_cast<size_t>(end.value)].q.coeffs());
  EXPECT_NE(d.message.find("step 2 of 5 failed"), std::string::npos) << d.message;
  EXPECT_NE(d.message.find("'bar1000'"), std::string::npos) << d.message;
  // Left at step 1, joints holding.
  ASSERT_EQ(steps.size(), 1u);
  EXPECT_EQ(c.m.body(end).pose.x, steps[0][static_cast<size_t>(end.value)].x);
  expect_joints_hold(c.m, 1e-9);
}

// Toward 3.45 from the shoulder (beyond r(0.5) = 3.3935; the links stretch to 3.5): the elbow
// stops at 0.5 rad.
TEST(Reach, ArmPastItsElbowLimitStopsAtTheNearestPose) {
  expect_arm_stops_at_its_limit(3.45 * Vec3(std::cos(0.9), std::sin(0.9), 0), 10);
}

// Toward 1.2 from the shoulder (inside r(2) = 1.9373): the elbow stops at 2 rad.
TEST(Reach, ArmFoldedPastItsElbowLimitStopsAtTheNearestPose) {
  expect_arm_stops_at_its_limit(1.2 * Vec3(std::cos(2.0), std::sin(2.0), 0), 20);
}

// A crank-rocker four-bar (ground 3, crank 1, coupler 3, rocker 2; pivots at the origin and at
// (3, 0)) with a hand pinned at the rocker's tip B: the loop lets B swing only between the
// rocker's dead points, where crank and coupler are in line (|B| = 2 and |B| = 4). A target off
// B's circle and angularly past the dead point |B| = 4 at E = (3.5, sqrt(3.75)) is out of reach
// because of the loop (each link alone reaches it); the nearest pose puts B at E.
struct FourBar {
  Model m;
  BodyId crank, coupler, rocker, hand;
  FourBar() {
    const Vec3 a(0, 1, 0);  // the crank at 90 degrees
    // B: 3 from A and 2 from the rocker's pivot, the upper branch.
    const Vec3 d(3, 0, 0);
    const double ad = (d - a).norm();
    const double along = (9 - 4 + ad * ad) / (2 * ad);
    const Vec3 u = (d - a) / ad;
    const Vec3 b = a + along * u + std::sqrt(9 - along * along) * Vec3(-u.y(), u.x(), 0);
    crank = add_bar(m, "crank", Vec3::Zero(), std::atan2(a.y(), a.x()), 1);
    coupler = add_bar(m, "coupler", a, std::atan2(b.y() - a.y(), b.x() - a.x()), 3);
    rocker = add_bar(m, "rocker", d, std::atan2(b.y(), b.x() - 3), 2);
    Body h;
    h.name = "hand";
    h.pose = Pose::from(b, Vec3::Zero());
    hand = m.add_body(h);
    m.add_joint(revolute(Model::kWorld, crank, Vec3::Zero()));
    m.add_joint(revolute(crank, coupler, Vec3(1, 0, 0)));
    Joint cr = revolute(coupler, rocker, Vec3(3, 0, 0));
    cr.p2 = Vec3(2, 0, 0);
    m.add_joint(cr);
    m.add_joint(revolute(Model::kWorld, rocker, d));
    m.add_joint(pin(rocker, hand, Vec3(2, 0, 0)));
  }
  static Vec3 dead_point() { return Vec3(3.5, std::sqrt(3.75), 0); }
  // Off the circle (1 from the rocker's pivot), at 60 degrees: past the dead point at 75.5 (the
  // distance to B grows with the angle between them), 3.6 from the crank's pivot (crank and
  // coupler reach 4: the joints' lengths do not tell it).
  static Vec3 target() {
    const double a = 60 * kPi / 180;
    return Vec3(3, 0, 0) + 1.0 * Vec3(std::cos(a), std::sin(a), 0);
  }
};

// The hand dragged in one step from where the assembly put it (B at 90 degrees of the crank) to
// the target: out of reach, the nearest pose B at the dead point. (On B's circle past the dead
// point the target is farther than crank and coupler stretch: the joints' lengths tell that.)
TEST(Reach, FourBarPastItsDeadPointStopsThere) {
  FourBar f;
  ASSERT_TRUE(assemble(f.m).converged);
  const std::vector<Pose> before = f.m.poses();
  Dragger drag(f.m, f.hand);
  const SolveResult r = drag.move_to(Pose::from(FourBar::target(), Vec3::Zero()));
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_FALSE(r.converged);
  // A long step: the held step's Newton steps (5: two whole steps that leave most of the misfit
  // end them) before it pulls, and the pull's (19; 23 before its curve search fitted the three
  // values once a point overshot, 21 before the pull's least damping was raised to 1e-8).
  EXPECT_LE(r.iterations, 25);
  EXPECT_NEAR(r.distance_left, (FourBar::target() - FourBar::dead_point()).norm(), 1e-9);
  expect_joints_hold(f.m, 1e-9, &r.poses);
  // B is at the dead point (where it moves only to second order: the pose to the root of the
  // distance's precision), crank and coupler in line.
  EXPECT_LT((r.poses[static_cast<size_t>(f.hand.value)].x - FourBar::dead_point()).norm(), 1e-4);
  EXPECT_NEAR(std::remainder(angle_of(r.poses[static_cast<size_t>(f.crank.value)]) -
                                 angle_of(r.poses[static_cast<size_t>(f.coupler.value)]),
                             2 * kPi),
              0, 1e-4);
  expect_unchanged(f.m, before);
}

// The held solve a drag step begins with (Session::Stuck::StopWhenSlow) gives up on the four-bar
// held past its dead point after two whole Newton steps that each leave more than half the
// misfit (the steps settle on a least-squares misfit: 0.56, 0.51, 0.50), where the held solve
// that stops only at a failed step takes 13; a target in reach is solved as that one solves it,
// to the same bits, and is not called slow.
TEST(Reach, HeldSolveStopsAtSlowWholeSteps) {
  FourBar f;
  ASSERT_TRUE(assemble(f.m).converged);
  std::vector<bool> held(static_cast<size_t>(f.m.body_count()), false);
  held[static_cast<size_t>(f.hand.value)] = true;
  Session slow(f.m, SolveOptions{}, held, Session::Stuck::StopWhenSlow);
  Session stop(f.m, SolveOptions{}, held, Session::Stuck::Stop);
  std::vector<Pose> a = f.m.poses();
  a[static_cast<size_t>(f.hand.value)] = Pose::from(FourBar::target(), Vec3::Zero());
  std::vector<Pose> b = a;
  const SolveResult s = slow.solve(a), t = stop.solve(b);
  EXPECT_EQ(s.status, SolveStatus::Stalled);
  EXPECT_TRUE(slow.slowed());
  EXPECT_LE(s.iterations, 5);
  EXPECT_EQ(t.status, SolveStatus::Stalled);
  EXPECT_FALSE(stop.slowed());
  EXPECT_GT(t.iterations, 10);
  // B at 100 degrees from the rocker's pivot, in reach.
  const Vec3 on(3 + 2 * std::cos(100 * kPi / 180), 2 * std::sin(100 * kPi / 180), 0);
  a = f.m.poses();
  a[static_cast<size_t>(f.hand.value)] = Pose::from(on, Vec3::Zero());
  b = a;
  const SolveResult u = slow.solve(a), v = stop.solve(b);
  ASSERT_TRUE(u.converged) << u.message;
  ASSERT_TRUE(v.converged) << v.message;
  EXPECT_FALSE(slow.slowed());
  EXPECT_EQ(u.iterations, v.iterations);
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].x, b[k].x) << k;
    EXPECT_EQ(a[k].q.coeffs(), b[k].q.coeffs()) << k;
  }
}

// The hand dragged along B's circle (2 from the rocker's pivot) from where the assembly put it
// (94.9 degrees) toward 60 degrees in 40 steps: the steps up to the dead point (75.5 degrees) are
// made; the first past it is out of reach (farther than crank and coupler stretch, 4 from the
// crank's pivot, but the stretched pair breaks the loop: pulled), with B at the dead point, the
// distance from there to that step's target, and within the aim of 20 iterations.
TEST(Reach, FourBarDraggedAcrossItsDeadPointStopsThere) {
  FourBar f;
  ASSERT_TRUE(assemble(f.m).converged);
  const Vec3 pivot(3, 0, 0);
  const Vec3 b0 = f.m.body(f.hand).pose.x - pivot;
  const double from = std::atan2(b0.y(), b0.x()), to = 60 * kPi / 180;
  const int steps = 40;
  Dragger drag(f.m, f.hand);
  std::vector<Pose> last = f.m.poses();
  for (int k = 1; k <= steps; ++k) {
    const double a = from + (to - from) * k / steps;
    const Vec3 t = pivot + 2 * Vec3(std::cos(a), std::sin(a), 0);
    const SolveResult r = drag.move_to(Pose::from(t, Vec3::Zero()));
    const Vec3 dead = FourBar::dead_point() - pivot;
    if (a >= std::atan2(dead.y(), dead.x())) {
      ASSERT_TRUE(r.converged) << k << ": " << r.message;
      last = f.m.poses();
      continue;
    }
    ASSERT_EQ(r.status, SolveStatus::OutOfReach) << k << ": " << r.message;
    EXPECT_LE(r.iterations, 20);
    EXPECT_NEAR(r.distance_left, (t - FourBar::dead_point()).norm(), 1e-9);
    expect_joints_hold(f.m, 1e-9, &r.poses);
    EXPECT_LT((r.poses[static_cast<size_t>(f.hand.value)].x - FourBar::dead_point()).norm(), 1e-4);
    expect_unchanged(f.m, last);
    return;
  }
  FAIL() << "no step past the dead point";
}

// The same pull as a workbench's mouse drag makes it (Puller): the model goes to the nearest
// pose, joints exact; a reachable point is met.
TEST(Reach, PullerMovesTheModelToTheNearestPose) {
  FourBar f;
  ASSERT_TRUE(assemble(f.m).converged);
  Puller pull(f.m, f.hand, Vec3::Zero());
  const SolveResult r = pull.pull_to(FourBar::target());
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_FALSE(r.converged);
  EXPECT_LE(r.iterations, 40);
  EXPECT_NEAR(r.distance_left, (FourBar::target() - FourBar::dead_point()).norm(), 1e-9);
  EXPECT_EQ(r.constraints.size(), 5u);
  EXPECT_TRUE(r.violated().empty());
  EXPECT_LT((f.m.body(f.hand).pose.x - FourBar::dead_point()).norm(), 1e-4);
  expect_joints_hold(f.m, 1e-9);
  // Back on the arc: B at 100 degrees from the rocker's pivot is reached.
  const Vec3 on(3 + 2 * std::cos(100 * kPi / 180), 2 * std::sin(100 * kPi / 180), 0);
  const SolveResult back = pull.pull_to(on);
  EXPECT_TRUE(back.converged) << back.message;
  EXPECT_LE(back.iterations, 40);
  EXPECT_LT((f.m.body(f.hand).pose.x - on).norm(), 1e-9);
  expect_joints_hold(f.m, 1e-9);
  EXPECT_THROW(Puller(f.m, Model::kWorld, Vec3::Zero()), std::invalid_argument);
}

// A slider on a segment of the x axis from 0 to 2 dragged past its end and off the line: it stops
// at the end, (2, 0, 0).
TEST(Reach, SliderPastItsBoundStopsAtTheEnd) {
  Model m;
  Body b;
  b.name = "slider";
  b.pose = Pose::from(Vec3(1, 0, 0), Vec3::Zero());
  const BodyId slider = m.add_body(b);
  Joint j;
  j.body2 = slider;
  j.guide = Guide{GuideKind::Axial, Vec3::UnitX(), 0, 2, 0, {}};
  m.add_joint(j);
  ASSERT_TRUE(assemble(m).converged);
  const std::vector<Pose> before = m.poses();
  Dragger drag(m, slider);
  const Vec3 t(2.5, 0.3, 0.2);
  const SolveResult r = drag.move_to(Pose::from(t, Vec3::Zero()));
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_LE(r.iterations, 40);
  EXPECT_NEAR(r.distance_left, (t - Vec3(2, 0, 0)).norm(), 1e-9);
  EXPECT_LT((r.poses[static_cast<size_t>(slider.value)].x - Vec3(2, 0, 0)).norm(), 1e-9);
  EXPECT_TRUE(r.constraints[0].at_limit);
  expect_unchanged(m, before);
}

// The flying snake (samples/snake.dcl: five links pinned end to end, the tail's end sliding on a
// rod of the world between x = -1 and 1), a link's end dragged far above: the bound ends on the
// rod, so the step is told at once, the tail at the rod's point nearest the target and the links
// stretched from it (the nearest pose there is: no pose takes the link's end farther from the
// rod than the links' length). The held solve and the pull took 537-990 iterations here.
TEST(Reach, SnakeOnItsRodIsToldAtOnce) {
  ParseResult parsed = load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/snake.dcl");
  ASSERT_TRUE(parsed.ok()) << parsed.messages();
  Model m = std::move(*parsed.model);
  ASSERT_TRUE(assemble(m).converged);
  const std::vector<Pose> before = m.poses();
  const BodyId s4 = *m.find("s4"), tail = *m.find("tail");
  Dragger drag(m, s4);
  // s4's origin is four links (2) from the tail's end, which the rod keeps on x in [-1, 1].
  for (const Vec3& t : {Vec3(0, 10, 0), Vec3(3, 0, -6), Vec3(-7, 1, 1)}) {
    SCOPED_TRACE(t.transpose());
    Pose at = m.body(s4).pose;
    at.x = t;
    const SolveResult r = drag.move_to(at);
    ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
    EXPECT_EQ(r.iterations, 0);
    const Vec3 rod(std::clamp(t.x(), -1.0, 1.0), 0, 0);
    EXPECT_NEAR(r.distance_left, (t - rod).norm() - 2, 1e-9);
    EXPECT_LT((r.poses[static_cast<size_t>(tail.value)].x - rod).norm(), 1e-12);
    EXPECT_NEAR((r.poses[static_cast<size_t>(s4.value)].x - t).norm(), r.distance_left, 1e-9);
    expect_unchanged(m, before);
  }
}

// At any length: a thousand links on a ring (a planar guide: the first link's origin in the
// world's z = 0 plane, between 1 and 2 from the origin), the last link's origin dragged far out of
// reach: told without iterating, the anchor the ring's point nearest the target (its shadow on the
// plane, brought onto the ring), the links stretched from there toward it.
TEST(Reach, ThousandLinksOnARingAreToldAtOnce) {
  constexpr int n = 1000;
  Model m;
  std::vector<BodyId> bars;
  for (int i = 0; i < n; ++i) {
    Body b;
    b.name = "bar" + std::to_string(i);
    b.pose = Pose::from(Vec3(1.5 + i, 0, 0), Vec3::Zero());
    bars.push_back(m.add_body(b));
  }
  Joint ring;
  ring.body2 = bars[0];
  ring.guide = Guide{GuideKind::Planar, Vec3::UnitZ(), 1, 2, 0, {}};
  m.add_joint(ring);
  for (size_t i = 1; i < bars.size(); ++i) m.add_joint(pin(bars[i - 1], bars[i], Vec3(1, 0, 0)));
  ASSERT_TRUE(assemble(m).converged);
  const std::vector<Pose> before = m.poses();
  const BodyId end = bars.back();
  Dragger drag(m, end);
  for (const Vec3& target : {Vec3(-300, 400, 1200), Vec3(0.5, 0, -1500)}) {
    SCOPED_TRACE(target.transpose());
    Pose far = m.body(end).pose;
    far.x = target;
    const SolveResult r = drag.move_to(far);
    ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
    EXPECT_EQ(r.iterations, 0);
    const Vec3 shadow(target.x(), target.y(), 0);
    const Vec3 anchor = std::clamp(shadow.norm(), 1.0, 2.0) * shadow.normalized();
    EXPECT_NEAR(r.distance_left, (target - anchor).norm() - (n - 1), 1e-9);
    EXPECT_LT((r.poses[static_cast<size_t>(bars[0].value)].x - anchor).norm(), 1e-9);
    expect_unchanged(m, before);
  }
}

// The robot arm sample, assembled (its elbow bends 0.2 rad at least: angle limits). Its
// failures are fatal to the test: call it under ASSERT_NO_FATAL_FAILURE.
void load_robot_arm(Model& m) {
  ParseResult parsed = load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/robot-arm.dcl");
  ASSERT_TRUE(parsed.ok()) << parsed.messages();
  m = std::move(*parsed.model);
  ASSERT_TRUE(assemble(m).converged);
}

// The robot arm sample dragged beyond its elbow's limit (it never quite straightens: 0.2 rad at
// least, so the hand reaches 2 cos(0.1) from the shoulder at (0, 0.5, 0), short of the links'
// 2): the first step past that is out of reach, told within a few dozen iterations.
TEST(Reach, RobotArmPastItsElbowLimitIsOutOfReach) {
  Model m;
  ASSERT_NO_FATAL_FAILURE(load_robot_arm(m));
  const BodyId hand = *m.find("hand");
  Pose away = m.body(hand).pose;
  away.x = Vec3(3, 0.5, 0);
  const int steps = 40;
  const Pose start = m.body(hand).pose;
  const DragResult d = drag(m, hand, away, steps);
  ASSERT_FALSE(d.converged);
  const SolveResult& out = d.steps.back();
  ASSERT_EQ(out.status, SolveStatus::OutOfReach) << out.message;
  EXPECT_LE(out.iterations, 40);
  const double t = static_cast<double>(d.failed_step + 1) / steps;
  const Vec3 target = (1 - t) * start.x + t * away.x;
  const Vec3 shoulder(0, 0.5, 0);
  EXPECT_NEAR(out.distance_left, (target - shoulder).norm() - 2 * std::cos(0.1), 1e-9);
  EXPECT_TRUE(out.constraints[2].at_limit) << d.message;
}

// The robot arm's hand held at (5, 0.5, 0), beyond what its links stretch to (2.5 from the base's
// pivot): the arm stretched toward it breaks the elbow's limit, so the hand is pulled from where
// it is, to the nearest pose: the elbow at its limit, the hand 2 cos(0.1) from the shoulder,
// toward the target. Within a few dozen iterations, the model untouched.
TEST(Reach, RobotArmFarOutOfReachIsPulledToTheNearestPose) {
  Model m;
  ASSERT_NO_FATAL_FAILURE(load_robot_arm(m));
  const BodyId hand = *m.find("hand");
  const std::vector<Pose> before = m.poses();
  Pose away = m.body(hand).pose;
  away.x = Vec3(5, 0.5, 0);
  Dragger drag(m, hand);
  const SolveResult r = drag.move_to(away);
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_LE(r.iterations, 40);
  const Vec3 shoulder(0, 0.5, 0);
  EXPECT_NEAR(r.distance_left, (away.x - shoulder).norm() - 2 * std::cos(0.1), 1e-9);
  expect_joints_hold(m, 1e-9, &r.poses);
  const Vec3 at = r.poses[static_cast<size_t>(hand.value)].x;
  EXPECT_LT((at - (shoulder + 2 * std::cos(0.1) * Vec3::UnitX())).norm(), 1e-4);
  EXPECT_TRUE(r.constraints[2].at_limit) << r.message;
  EXPECT_NE(r.message.find("nearest pose"), std::string::npos) << r.message;
  expect_unchanged(m, before);
}

// The reachable step before the 1,000-link chain's first out of reach (0.04 short of stretched,
// from the gently curved pose) is made, the end exactly at its target, within a few dozen
// iterations: the held Newton steps fail there (the first-order model of a nearly stretched
// chain sees almost no way to change its reach; 338 iterations when the pull and then the held
// solve crawled on), and the chain straightened by the one factor that meets the target leaves
// the held solve nothing to do. The chain keeps its shape's sides: every link still turns the
// same way from the line to the end, by less.
TEST(Reach, ThousandLinkChainNearFullStretchConverges) {
  const int n = 1000;
  Chain c = Chain::gently_curved(n);
  ASSERT_TRUE(assemble(c.m).converged);
  const BodyId end = c.bars.back();
  const Pose start = c.m.body(end).pose;
  const std::vector<Pose> before = c.m.poses();
  const Pose target{start.q, start.x.normalized() * (n - 1 - 0.04)};
  Dragger drag(c.m, end);
  const SolveResult r = drag.move_to(target);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LE(r.iterations, 10);
  EXPECT_LE(r.max_residual, 1e-9);
  EXPECT_EQ(c.m.body(end).pose.x, target.x);
  expect_joints_hold(c.m, 1e-9);
  // Each link's angle from the line to the end, before and after: same sign, smaller.
  const Vec3 u = start.x.normalized();
  const Vec3 side = Vec3::UnitZ().cross(u);
  for (int i = 0; i < n - 1; ++i) {
    const size_t b = static_cast<size_t>(c.bars[static_cast<size_t>(i)].value);
    const Vec3 was = before[b].q * Vec3::UnitX(), now = c.m.poses()[b].q * Vec3::UnitX();
    const double a0 = std::atan2(was.dot(side), was.dot(u));
    const double a1 = std::atan2(now.dot(side), now.dot(u));
    if (std::abs(a0) < 1e-6) continue;
    EXPECT_GT(a0 * a1, 0) << i;
    EXPECT_LT(std::abs(a1), std::abs(a0)) << i;
  }
}

// The same chain dragged from its curved pose to 0.001 short of full stretch in 20 steps: every
// step made within a few dozen iterations, the end at each target.
TEST(Reach, ThousandLinkChainDraggedToNearlyStraight) {
  const int n = 1000;
  Chain c = Chain::gently_curved(n);
  ASSERT_TRUE(assemble(c.m).converged);
  const BodyId end = c.bars.back();
  const Pose start = c.m.body(end).pose;
  const Pose goal{start.q, start.x.normalized() * (n - 1 - 0.001)};
  std::vector<std::vector<Pose>> done;
  const DragResult d = drag(c.m, end, goal, 20, SolveOptions{}, &done);
  ASSERT_TRUE(d.converged) << d.message;
  for (const SolveResult& s : d.steps) EXPECT_LE(s.iterations, 40) << s.message;
  EXPECT_LT((c.m.body(end).pose.x - goal.x).norm(), 1e-12);
  expect_joints_hold(c.m, 1e-9);
}

// A 3-link arm (links 1, 2, 1.5) with a lamp hung from the middle link by a planar revolute (its
// origin 0.4 along the link, turned 0.8 rad from it) dragged by its hand far out of reach: the
// nearest pose is the arm stretched toward the target, the lamp carried with its link (where it
// sits on the link and how it is turned against it unchanged), told without iterating.
TEST(Reach, StretchedArmCarriesWhatHangsOffIt) {
  Chain arm({1.0, 2.0, 1.5}, {0.2, 0.9, -0.4}, true);
  const BodyId middle = arm.bars[1];
  const Pose m0 = arm.m.body(middle).pose;
  const BodyId lamp = add_bar(arm.m, "lamp", m0.apply(Vec3(0.4, 0, 0)), angle_of(m0) + 0.8, 0.6);
  arm.m.add_joint(revolute(middle, lamp, Vec3(0.4, 0, 0)));
  ASSERT_TRUE(assemble(arm.m).converged);
  const std::vector<Pose> before = arm.m.poses();
  Dragger drag(arm.m, arm.hand);
  const Vec3 t(-3, 5, 0);
  const SolveResult r = drag.move_to(Pose::from(t, Vec3::Zero()));
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_EQ(r.iterations, 0);
  EXPECT_NEAR(r.distance_left, t.norm() - 4.5, 1e-12);
  expect_joints_hold(arm.m, 1e-12, &r.poses);
  const Vec3 u = t.normalized();
  const Pose& mid = r.poses[static_cast<size_t>(middle.value)];
  const Pose& hung = r.poses[static_cast<size_t>(lamp.value)];
  EXPECT_LT((mid.x - u).norm(), 1e-12);
  EXPECT_LT((hung.x - (u + 0.4 * u)).norm(), 1e-12);
  EXPECT_NEAR(std::remainder(angle_of(hung) - angle_of(mid) - 0.8, 2 * kPi), 0, 1e-12);
  EXPECT_LT((r.poses[static_cast<size_t>(arm.hand.value)].x - 4.5 * u).norm(), 1e-12);
  expect_unchanged(arm.m, before);
}

// A Puller's point moved along the stretched boundary of a 2-link arm (links 2 and 1.5), 0.3
// beyond it, in 20 moves: each move is the arm stretched toward the point, without iterating,
// the hand 3.5 from the shoulder on the line to it and the model moved there.
TEST(Reach, PullerAlongTheStretchedBoundary) {
  Chain arm({2.0, 1.5}, {0.3, 1.2}, true);
  ASSERT_TRUE(assemble(arm.m).converged);
  Puller pull(arm.m, arm.hand, Vec3::Zero());
  for (int k = 0; k <= 20; ++k) {
    const double a = 0.4 + 0.05 * k;
    const Vec3 u(std::cos(a), std::sin(a), 0);
    const SolveResult r = pull.pull_to(3.8 * u);
    ASSERT_EQ(r.status, SolveStatus::OutOfReach) << k << ": " << r.message;
    EXPECT_EQ(r.iterations, 0) << k;
    EXPECT_NEAR(r.distance_left, 0.3, 1e-12) << k;
    EXPECT_TRUE(r.violated().empty()) << k;
    EXPECT_LT((arm.m.body(arm.hand).pose.x - 3.5 * u).norm(), 1e-12) << k;
    expect_joints_hold(arm.m, 1e-12);
  }
  // Back within reach the pull meets the point.
  const SolveResult back = pull.pull_to(Vec3(1, 2, 0));
  EXPECT_TRUE(back.converged) << back.message;
  EXPECT_LT((arm.m.body(arm.hand).pose.x - Vec3(1, 2, 0)).norm(), 1e-9);
}

// A chain of parallelograms (the FreeCAD GUI test's 100-part drag, smaller): `cranks` unit cranks
// pinned 1.5 apart along x, turned 60 degrees, neighbours joined by couplers of 1.5; revolutes
// about z, one degree of freedom: a coupler translates on a unit circle.
struct CrankChain {
  Model m;
  std::vector<BodyId> couplers;
  explicit CrankChain(int cranks) {
    const double turn = kPi / 3;
    const Vec3 tip(std::cos(turn), std::sin(turn), 0);
    auto revolute = [&](BodyId b1, BodyId b2, const Vec3& p1, const Vec3& p2) {
      Joint j = pin(b1, b2, p1);
      j.p2 = p2;
      j.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
      m.add_joint(j);
    };
    std::vector<BodyId> cs;
    for (int k = 0; k < cranks; ++k) {
      Body b;
      b.name = "crank" + std::to_string(k);
      b.pose = Pose::from(Vec3(1.5 * k, 0, 0), Vec3(0, 0, turn));
      b.center = Vec3(0.5, 0, 0);
      cs.push_back(m.add_body(b));
      revolute(Model::kWorld, cs.back(), Vec3(1.5 * k, 0, 0), Vec3::Zero());
    }
    for (int k = 0; k + 1 < cranks; ++k) {
      Body b;
      b.name = "coupler" + std::to_string(k);
      b.pose = Pose::from(Vec3(1.5 * k, 0, 0.1) + tip, Vec3::Zero());
      b.center = Vec3(0.75, 0, 0);
      couplers.push_back(m.add_body(b));
      revolute(cs[static_cast<size_t>(k)], couplers.back(), Vec3(1, 0, 0.1), Vec3::Zero());
      revolute(cs[static_cast<size_t>(k) + 1], couplers.back(), Vec3(1, 0, 0.1), Vec3(1.5, 0, 0));
    }
  }
};

// A Puller's point moved in reach: a coupler's middle along its circle, 1.5 degrees a move (the
// GUI test's drag). Each move meets the point. A pull that follows one which met its point damps
// its first step less (pull.cpp's kFollowDamping): it takes fewer Newton steps than a new Puller
// pulling from the same poses to the same point, and ends at the same pose.
TEST(Reach, PullerInReachFollowsInFewerSteps) {
  CrankChain chain(25);
  ASSERT_TRUE(assemble(chain.m).converged);
  const BodyId grabbed = chain.couplers[12];
  const Vec3 point(0.75, 0, 0), start = chain.m.body(grabbed).pose.apply(point);
  Puller pull(chain.m, grabbed, point);
  int fewer = 0;
  for (int k = 0; k <= 10; ++k) {
    const double a = kPi / 3 + 1.5 * kPi / 180 * k;
    const Vec3 to = start + Vec3(std::cos(a) - 0.5, std::sin(a) - std::sin(kPi / 3), 0);
    Model fresh = chain.m;
    const SolveResult r = pull.pull_to(to);
    ASSERT_TRUE(r.converged) << k << ": " << r.message;
    EXPECT_LT((chain.m.body(grabbed).pose.apply(point) - to).norm(), 1e-9) << k;
    expect_joints_hold(chain.m, 1e-9);
    const SolveResult first = Puller(fresh, grabbed, point).pull_to(to);
    ASSERT_TRUE(first.converged) << k << ": " << first.message;
    if (k == 0) {
      EXPECT_EQ(r.iterations, first.iterations);  // nothing to follow yet
    } else {
      EXPECT_LE(r.iterations, first.iterations) << k;
      fewer += r.iterations < first.iterations;
    }
    for (size_t b = 0; b < r.poses.size(); ++b) {
      EXPECT_LT((r.poses[b].x - first.poses[b].x).norm(), 1e-8) << k << ", body " << b;
    }
  }
  EXPECT_GE(fewer, 5);
}

// A Puller's point drawn frame after frame toward points off its path (the GUI test's drag, its
// cursor rounded to pixels): a coupler's middle translates on a unit circle, so the nearest pose
// puts it at the target's radial projection onto that circle, |r - 1| from the target (r the
// target's distance from the circle's centre). Inside the circle the valid poses bend toward the
// target and a Gauss-Newton step falls short by about (1 - r) of the error (the pull left that
// share of it a step, and stopped where a step's gain fell below the tolerance: 10.75 Newton
// steps a frame inside, up to 1e-6 off the distance and 1e-3 off the point); stretched to the
// curve's least point each step, it closes in superlinearly (5 Newton steps a frame; 7 inside
// before a step's promise left out the hard rows' yield, pull.cpp).
TEST(Reach, PullerOffItsCircleStopsAtTheRadialProjection) {
  CrankChain chain(25);
  ASSERT_TRUE(assemble(chain.m).converged);
  const BodyId grabbed = chain.couplers[12];
  const Vec3 point(0.75, 0, 0), start = chain.m.body(grabbed).pose.apply(point);
  const Vec3 centre = start - Vec3(std::cos(kPi / 3), std::sin(kPi / 3), 0);
  Puller pull(chain.m, grabbed, point);
  int inside = 0, frames_inside = 0;
  for (int k = 1; k <= 24; ++k) {
    const double a = kPi / 3 + 1.5 * kPi / 180 * k;
    // Off the circle by 0.01 to 0.1, inside and outside in turn.
    const double off = (k % 2 ? -1 : 1) * (0.01 + 0.09 * (k % 5) / 4.0);
    const Vec3 to = centre + (1 + off) * Vec3(std::cos(a), std::sin(a), 0);
    const SolveResult r = pull.pull_to(to);
    ASSERT_EQ(r.status, SolveStatus::OutOfReach) << k << ": " << r.message;
    EXPECT_NEAR(r.distance_left, std::abs(off), 1e-9) << k;
    const Vec3 at = chain.m.body(grabbed).pose.apply(point);
    EXPECT_LT((at - (centre + Vec3(std::cos(a), std::sin(a), 0))).norm(), 1e-5) << k;
    expect_joints_hold(chain.m, 1e-9);
    EXPECT_LE(r.iterations, 6) << k;  // 5
    if (off < 0) inside += r.iterations, ++frames_inside;
  }
  EXPECT_LE(2 * inside, 11 * frames_inside);  // 5 a frame
}

// The limited arm's hand held at (5, 2, 0), beyond what its links stretch to (3.5): the arm
// stretched toward it breaks the elbow's limit (0.5 rad at least), so the hand is pulled, to the
// nearest pose: the elbow at its limit, the hand r(0.5) from the shoulder toward the target.
// Where the pull was linear (the Gauss-Newton step too long by |t| / r(0.5)) it stopped at 40
// iterations and reported the links' bound (1.885) instead of the true distance (1.992).
TEST(Reach, LimitedArmFarOutOfReachIsPulledToItsLimit) {
  LimitedArm arm;
  ASSERT_TRUE(assemble(arm.m).converged);
  const std::vector<Pose> before = arm.m.poses();
  Dragger drag(arm.m, arm.hand);
  const Vec3 t(5, 2, 0);
  const SolveResult r = drag.move_to(Pose::from(t, Vec3::Zero()));
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_LE(r.iterations, 20);
  const double reach = LimitedArm::reach(LimitedArm::bend_min);
  EXPECT_NEAR(r.distance_left, t.norm() - reach, 1e-9);
  EXPECT_NE(r.message.find("nearest pose"), std::string::npos) << r.message;
  expect_joints_hold(arm.m, 1e-9, &r.poses);
  const Pose& upper = r.poses[static_cast<size_t>(arm.upper.value)];
  const Pose& forearm = r.poses[static_cast<size_t>(arm.forearm.value)];
  EXPECT_NEAR(std::remainder(angle_of(forearm) - angle_of(upper) - LimitedArm::bend_min, 2 * kPi),
              0, 1e-9);
  const double direction = std::atan2(t.y(), t.x());
  EXPECT_NEAR(std::remainder(
                  angle_of(upper) - LimitedArm::shoulder(direction, LimitedArm::bend_min), 2 * kPi),
              0, 1e-4);
  EXPECT_LT((r.poses[static_cast<size_t>(arm.hand.value)].x - reach * t.normalized()).norm(), 1e-4);
  EXPECT_TRUE(r.constraints[1].at_limit);
  expect_unchanged(arm.m, before);
}

// A planar 2-link arm (2 and 1.5, revolutes about z: the angle joints keep it in the xy plane, a
// hand pinned at its tip) whose hand is dragged out of the plane: the nearest pose is the
// nearest in the plane to the target's projection, at height |z| below or above it. Within the
// plane's reach the hand goes to the projection (distance |z|); beyond it the arm is stretched
// toward it (distance hypot(z, |t_xy| - 3.5)). The stretched path toward the target itself
// leaves the plane (it breaks the angle joints), so the hand is pulled.
struct PlanarArm {
  Model m;
  BodyId upper, forearm, hand;
  PlanarArm() {
    upper = add_bar(m, "upper", Vec3::Zero(), 0.3, 2);
    const Vec3 elbow = 2 * Vec3(std::cos(0.3), std::sin(0.3), 0);
    forearm = add_bar(m, "forearm", elbow, 1.5, 1.5);
    Body h;
    h.name = "hand";
    h.pose = Pose::from(elbow + 1.5 * Vec3(std::cos(1.5), std::sin(1.5), 0), Vec3::Zero());
    hand = m.add_body(h);
    m.add_joint(revolute(Model::kWorld, upper, Vec3::Zero()));
    m.add_joint(revolute(upper, forearm, Vec3(2, 0, 0)));
    m.add_joint(pin(forearm, hand, Vec3(1.5, 0, 0)));
  }
};

void expect_pulled_out_of_plane(const Vec3& t, int most) {
  PlanarArm arm;
  ASSERT_TRUE(assemble(arm.m).converged);
  const std::vector<Pose> before = arm.m.poses();
  Dragger drag(arm.m, arm.hand);
  const SolveResult r = drag.move_to(Pose::from(t, Vec3::Zero()));
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_LE(r.iterations, most);
  const Vec3 flat(t.x(), t.y(), 0);
  const double beyond = std::max(0.0, flat.norm() - 3.5);
  EXPECT_NEAR(r.distance_left, std::hypot(t.z(), beyond), 1e-9);
  expect_joints_hold(arm.m, 1e-9, &r.poses);
  const Vec3 at = r.poses[static_cast<size_t>(arm.hand.value)].x;
  const Vec3 nearest = beyond > 0 ? Vec3(3.5 * flat.normalized()) : flat;
  // (The distance is of second order in an error of the pose there: the pose to its root.)
  EXPECT_LT((at - nearest).norm(), 1e-4) << at.transpose();
  expect_unchanged(arm.m, before);
}

TEST(Reach, PlanarArmDraggedOutOfItsPlaneStopsAboveTheProjection) {
  expect_pulled_out_of_plane(Vec3(1, 2, 0.5), 22);  // 19
  expect_pulled_out_of_plane(Vec3(1, 2, -1), 22);   // 19
}

TEST(Reach, PlanarArmDraggedOutOfItsPlaneAndReachIsStretchedInIt) {
  expect_pulled_out_of_plane(Vec3(3, 2.5, 0.5), 22);  // 21
  expect_pulled_out_of_plane(Vec3(3, 2.5, 1), 22);    // 19
}

// The planar arm with a hand on a wrist (a revolute whose twist is kept within +-1 rad) held
// where it is but turned about z: within the wrist's range the step is made; past it the origin
// can stay (the arm holds the wrist where it is) but the rotation cannot, and the step is out of
// reach by its rotation: the nearest pose has the wrist at its limit, the hand's origin at the
// target, angle_left what the wrist cannot turn (the turn less 1 rad). Before, the held solve
// went on to its stall rule (404 iterations) and reported no pose.
struct WristArm {
  Model m;
  BodyId forearm, hand;
  // `ball`: the wrist a ball joint instead, the robot arm's (samples/robot-arm.dcl): the hand's
  // x axis within a cone of 0.5 rad about the forearm's, its twist about it within +-1 rad.
  explicit WristArm(bool ball = false) {
    const BodyId upper = add_bar(m, "upper", Vec3::Zero(), 0.3, 2);
    const Vec3 elbow = 2 * Vec3(std::cos(0.3), std::sin(0.3), 0);
    forearm = add_bar(m, "forearm", elbow, 1.5, 1.5);
    hand = add_bar(m, "hand", elbow + 1.5 * Vec3(std::cos(1.5), std::sin(1.5), 0), 1.5, 0.5);
    m.add_joint(revolute(Model::kWorld, upper, Vec3::Zero()));
    m.add_joint(revolute(upper, forearm, Vec3(2, 0, 0)));
    Joint wrist = revolute(forearm, hand, Vec3(1.5, 0, 0));
    wrist.twist = TwistSpec{Vec3::UnitX(), Vec3::UnitX(), -1, 1};
    if (ball) {
      wrist.angle = AngleSpec{Vec3::UnitX(), Vec3::UnitX(), 0, 0.5};
      wrist.twist = TwistSpec{Vec3::UnitY(), Vec3::UnitY(), -1, 1};
    }
    m.add_joint(wrist);
  }
};

void expect_turn_stops_at_the_limit(double turn) {
  WristArm arm;
  ASSERT_TRUE(assemble(arm.m).converged);
  const std::vector<Pose> before = arm.m.poses();
  const Pose start = arm.m.body(arm.hand).pose;
  const Pose target{(Quat(Eigen::AngleAxisd(turn, Vec3::UnitZ())) * start.q).normalized(), start.x};
  Dragger drag(arm.m, arm.hand);
  const SolveResult r = drag.move_to(target);
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_LE(r.iterations, 25);  // 20 and 22: the held step's, the origin's pull and the turn's
  EXPECT_EQ(r.held.value, arm.hand.value);
  EXPECT_NEAR(r.angle_left, turn - 1, 1e-9);
  EXPECT_LE(r.distance_left, 1e-9);
  EXPECT_NE(r.message.find("rad from its target's rotation"), std::string::npos) << r.message;
  expect_joints_hold(arm.m, 1e-9, &r.poses);
  const Pose& hand = r.poses[static_cast<size_t>(arm.hand.value)];
  const Pose& forearm = r.poses[static_cast<size_t>(arm.forearm.value)];
  EXPECT_LT((hand.x - start.x).norm(), 1e-9);
  EXPECT_NEAR(std::remainder(angle_of(hand) - angle_of(forearm) - 1, 2 * kPi), 0, 1e-9);
  EXPECT_TRUE(r.constraints[2].at_limit);
  expect_unchanged(arm.m, before);
}

TEST(Reach, WristTurnedPastItsLimitStopsThere) {
  expect_turn_stops_at_the_limit(1.5);
  expect_turn_stops_at_the_limit(2.5);
}

TEST(Reach, WristTurnedWithinItsLimitIsMade) {
  WristArm arm;
  ASSERT_TRUE(assemble(arm.m).converged);
  const Pose start = arm.m.body(arm.hand).pose;
  const Pose target{(Quat(Eigen::AngleAxisd(0.8, Vec3::UnitZ())) * start.q).normalized(), start.x};
  Dragger drag(arm.m, arm.hand);
  const SolveResult r = drag.move_to(target);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.angle_left, 0);
  EXPECT_LT(arm.m.body(arm.hand).pose.q.angularDistance(target.q), 1e-9);
  expect_joints_hold(arm.m, 1e-9);
}

// A ball wrist's cone and twist (WristArm(true)'s, the robot arm's) at poses.
double cone_of(const Pose& forearm, const Pose& hand) {
  return angle_between(forearm.q * Vec3::UnitX(), hand.q * Vec3::UnitX());
}
double twist_of(const Pose& forearm, const Pose& hand) {
  return twist_angle(forearm.q * Vec3::UnitX(), hand.q * Vec3::UnitX(), forearm.q * Vec3::UnitY(),
                     hand.q * Vec3::UnitY());
}

// WristArm's planar arm with its ball wrist, the hand along the forearm, held where it is and
// turned by `turn` about `axis` (world): past the cone or the twist the nearest pose has the wrist
// at that limit, its origin at the target's, and angle_left what the limit leaves of the turn.
void expect_ball_wrist_turn_stops(const Vec3& axis, double turn, double cone, double twist,
                                  double left) {
  WristArm arm(true);
  ASSERT_TRUE(assemble(arm.m).converged);
  const std::vector<Pose> before = arm.m.poses();
  const Pose start = arm.m.body(arm.hand).pose;
  const Pose target{(Quat(Eigen::AngleAxisd(turn, axis)) * start.q).normalized(), start.x};
  Dragger drag(arm.m, arm.hand);
  const SolveResult r = drag.move_to(target);
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_LE(r.iterations, 25);  // 18 past the cone, 12 past the twist
  EXPECT_LE(r.distance_left, 1e-9);
  EXPECT_NEAR(r.angle_left, left, 1e-9);
  expect_joints_hold(arm.m, 1e-9, &r.poses);
  const Pose& hand = r.poses[static_cast<size_t>(arm.hand.value)];
  const Pose& forearm = r.poses[static_cast<size_t>(arm.forearm.value)];
  EXPECT_LT((hand.x - start.x).norm(), 1e-9);
  EXPECT_NEAR(r.angle_left, hand.q.angularDistance(target.q), 1e-12);
  EXPECT_NEAR(cone_of(forearm, hand), cone, 1e-9);
  EXPECT_NEAR(twist_of(forearm, hand), twist, 1e-9);
  EXPECT_TRUE(r.constraints[2].at_limit);
  expect_unchanged(arm.m, before);
}

TEST(Reach, BallWristTurnedPastItsConeStopsAtTheCone) {
  // About the arm's plane's normal: the hand's axis swings in the plane to the cone's edge.
  expect_ball_wrist_turn_stops(Vec3::UnitZ(), 2.5, 0.5, 0, 2);
}

TEST(Reach, BallWristTurnedPastItsTwistStopsAtTheTwist) {
  // About the forearm's axis (at 1.5 rad in the plane): the twist stops at its limit.
  expect_ball_wrist_turn_stops(Vec3(std::cos(1.5), std::sin(1.5), 0), 1.5, 0, 1, 0.5);
}

// The robot arm sample's hand held where it is and turned 2.5 rad about z, against its wrist's
// cone (0.5 rad) and twist (+-1 rad); its arm (base, shoulder, elbow at its limit) holds the wrist
// where it is. The swing stops at the cone's edge; the arm's plane is tilted by the base's turn
// (0.018 rad about y), so no closed form gives the angle left, but the nearest pose is at least
// as near as the hand swung in the forearm's plane to the cone's edge (an allowed pose). Before:
// 466 iterations and no pose (the turn's pull crawled along the cone and the held solve ran to
// its stall rule).
TEST(Reach, RobotArmHandTurnedAgainstItsConeAndTwistStopsAtTheCone) {
  Model m;
  ASSERT_NO_FATAL_FAILURE(load_robot_arm(m));
  const BodyId hand = *m.find("hand");
  const BodyId forearm = *m.find("forearm");
  const std::vector<Pose> before = m.poses();
  const Pose start = m.body(hand).pose;
  const Pose target{(Quat(Eigen::AngleAxisd(2.5, Vec3::UnitZ())) * start.q).normalized(), start.x};
  Dragger drag(m, hand);
  const SolveResult r = drag.move_to(target);
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  // 32: the held step's 10, the origin's pull 1, the turn 21 (along the cone's rim its damped
  // steps converged linearly, 70; reduced quasi-Newton steps on the rim's free directions,
  // pull.cpp's rim_steps, take it there superlinearly; measured by the sine of the tilt it
  // stopped after 20, 3.7e-5 rad short).
  EXPECT_LE(r.iterations, 40);
  EXPECT_LE(r.distance_left, 1e-9);
  expect_joints_hold(m, 1e-9, &r.poses);
  const Pose& h = r.poses[static_cast<size_t>(hand.value)];
  const Pose& f = r.poses[static_cast<size_t>(forearm.value)];
  EXPECT_LT((h.x - start.x).norm(), 1e-9);
  EXPECT_NEAR(cone_of(f, h), 0.5, 1e-9);
  EXPECT_LE(std::abs(twist_of(f, h)), 1);
  EXPECT_TRUE(r.constraints[3].at_limit);
  EXPECT_NEAR(r.angle_left, h.q.angularDistance(target.q), 1e-12);
  const Quat swung = f.q * Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()));
  EXPECT_NEAR(cone_of(f, Pose{swung, h.x}), 0.5, 1e-12);
  EXPECT_LE(r.angle_left, swung.angularDistance(target.q) + 1e-9);
  EXPECT_GT(r.angle_left, 2.0);  // the cone takes at most 0.5 + 0.023 (where the hand began)
  expect_unchanged(m, before);
}

// A door on a revolute at its origin (twist within +-1 rad), the only body: turned to 1.5 rad it
// stops at 1.
TEST(Reach, DoorTurnedPastItsLimitStopsThere) {
  Model m;
  const BodyId door = add_bar(m, "door", Vec3::Zero(), 0, 1);
  Joint j = revolute(Model::kWorld, door, Vec3::Zero());
  j.twist = TwistSpec{Vec3::UnitX(), Vec3::UnitX(), -1, 1};
  m.add_joint(j);
  ASSERT_TRUE(assemble(m).converged);
  const std::vector<Pose> before = m.poses();
  Dragger drag(m, door);
  const SolveResult r = drag.move_to(Pose::from(Vec3::Zero(), Vec3(0, 0, 1.5)));
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_LE(r.iterations, 20);  // 16
  EXPECT_NEAR(r.angle_left, 0.5, 1e-9);
  EXPECT_NEAR(angle_of(r.poses[static_cast<size_t>(door.value)]), 1, 1e-9);
  expect_unchanged(m, before);
}

// The robot arm's wrist (samples/robot-arm.dcl, a ball joint: the hand's x within 0.5 rad of the
// forearm's, its twist within +-1) as a box of coordinates, for a search independent of the
// solver: the hand's rotation in the forearm's frame is W = S(alpha, phi) Rx(tau), a swing by phi
// about (0, cos alpha, sin alpha) after a turn about x. The cone is phi. The twist (twist.hpp:
// from the projections of the two y axes on the plane across the bisector of the two x axes) is
// g(tau - alpha) - g(-alpha), g(psi) = atan2(cos(phi / 2) sin psi, cos psi): the projection keeps
// the swing's axis and shortens the direction across it by cos(phi / 2), and the swing changes
// neither projection. So W is given by (alpha, phi, twist) in a box: alpha any, phi in [0, 0.5],
// twist in [-1, 1].
struct WristBox {
  static constexpr double cone = 0.5, twist = 1;
  double alpha = 0, phi = 0, t = 0;

  Quat rotation() const {
    const double k = std::cos(phi / 2);
    const double from = std::atan2(k * std::sin(-alpha), std::cos(-alpha)) + t;
    const double psi = std::atan2(std::sin(from) / k, std::cos(from));
    const Vec3 axis(0, std::cos(alpha), std::sin(alpha));
    return (Quat(Eigen::AngleAxisd(phi, axis)) *
            Quat(Eigen::AngleAxisd(psi + alpha, Vec3::UnitX())))
        .normalized();
  }
  // The coordinates of an allowed W (the inverse of rotation()).
  static WristBox of(const Quat& w) {
    WristBox b;
    const Vec3 x = w * Vec3::UnitX();
    b.phi = angle_between(Vec3::UnitX(), x);
    const Vec3 s = Vec3::UnitX().cross(x);
    if (s.norm() > 1e-12) b.alpha = std::atan2(s.z(), s.y());
    b.t = twist_angle(Vec3::UnitX(), x, Vec3::UnitY(), w * Vec3::UnitY());
    return b;
  }
  void clamp() {
    phi = std::clamp(phi, 0.0, cone);
    t = std::clamp(t, -twist, twist);
  }
};

// The least angle between forearm * W and `target` over the wrist's box, by a pattern search
// from `from` (each coordinate stepped both ways, clamped to the box; the steps halved when none
// gains) down to steps of 1e-10: a local least.
WristBox nearest_in_box(const Quat& forearm, const Quat& target, WristBox from, double step) {
  auto angle = [&](const WristBox& b) { return (forearm * b.rotation()).angularDistance(target); };
  from.clamp();
  double best = angle(from);
  while (step > 1e-10) {
    bool gained = false;
    for (int c = 0; c < 3; ++c) {
      for (double sign : {1.0, -1.0}) {
        WristBox b = from;
        (c == 0 ? b.alpha : c == 1 ? b.phi : b.t) += sign * step;
        b.clamp();
        const double a = angle(b);
        if (a < best) best = a, from = b, gained = true;
      }
    }
    if (!gained) step /= 2;
  }
  return from;
}

// The same from every point of a grid over the box (alpha by 20 degrees, phi by 0.25, twist by
// 0.5), the least of the local leasts: the nearest allowed rotation, found without the solver.
double nearest_allowed_angle(const Quat& forearm, const Quat& target) {
  double best = HUGE_VAL;
  for (int i = 0; i < 18; ++i) {
    for (int j = 0; j <= 2; ++j) {
      for (int k = -2; k <= 2; ++k) {
        WristBox b;
        b.alpha = i * kPi / 9, b.phi = 0.25 * j, b.t = 0.5 * k;
        const WristBox at = nearest_in_box(forearm, target, b, 0.1);
        best = std::min(best, (forearm * at.rotation()).angularDistance(target));
      }
    }
  }
  return best;
}

TEST(Reach, WristBoxGivesTheConeAndTwistAsked) {
  for (const WristBox& b : {WristBox{0.3, 0.5, 1}, WristBox{2, 0.2, -0.7},
                            WristBox{-2.5, 0.45, 0.1}, WristBox{0, 0, -1}}) {
    const Pose f{Quat::Identity(), Vec3::Zero()}, h{b.rotation(), Vec3::Zero()};
    EXPECT_NEAR(cone_of(f, h), b.phi, 1e-12);
    EXPECT_NEAR(twist_of(f, h), b.t, 1e-12);
    const WristBox back = WristBox::of(b.rotation());
    EXPECT_LT(back.rotation().angularDistance(b.rotation()), 1e-12);
  }
}

// The robot arm's hand held where it is and turned by `turn` about `axis` (world). Its origin
// held there, the arm (base, shoulder, elbow: three turns for the origin's three coordinates)
// cannot move, so the hand turns by its wrist alone: where the turn is within the wrist's cone
// and twist the step is made. Past them the result must not lie: the pose returned is valid,
// with the hand's origin at the target's and no farther from the target's rotation than the
// start (the turn). Told out of reach, it is the nearest: no allowed rotation of the wrist next
// to it is nearer by 1e-8 rad (a local search from it in WristBox's coordinates), and it is
// within 1e-8 rad of the nearest of all (a search over the whole box). Within `most` iterations.
void expect_robot_hand_turn(const Vec3& axis, double turn, int most) {
  constexpr double gap = 1e-8;
  SCOPED_TRACE("turned " + std::to_string(turn) + " about (" + std::to_string(axis.x()) + ", " +
               std::to_string(axis.y()) + ", " + std::to_string(axis.z()) + ")");
  Model m;
  ASSERT_NO_FATAL_FAILURE(load_robot_arm(m));
  const BodyId hand = *m.find("hand");
  const BodyId forearm = *m.find("forearm");
  const std::vector<Pose> before = m.poses();
  const Pose start = m.body(hand).pose;
  const Pose target{(Quat(Eigen::AngleAxisd(turn, axis.normalized())) * start.q).normalized(),
                    start.x};
  Dragger drag(m, hand);
  const SolveResult r = drag.move_to(target);
  EXPECT_LE(r.iterations, most);
  const Quat f = before[static_cast<size_t>(forearm.value)].q;
  const double nearest = nearest_allowed_angle(f, target.q);
  if (nearest < 1e-9) {
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_LT(m.body(hand).pose.q.angularDistance(target.q), 1e-9);
    expect_joints_hold(m, 1e-9);
    return;
  }
  expect_unchanged(m, before);
  // Every other one ends at the nearest pose.
  ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
  EXPECT_LE(r.distance_left, 1e-9);
  expect_joints_hold(m, 1e-9, &r.poses);
  const Pose& h = r.poses[static_cast<size_t>(hand.value)];
  EXPECT_LT((h.x - start.x).norm(), 1e-9);
  // The arm did not move (the wrist's rotations are all the hand has).
  EXPECT_LT(r.poses[static_cast<size_t>(forearm.value)].q.angularDistance(f), 1e-6);
  EXPECT_NEAR(r.angle_left, h.q.angularDistance(target.q), 1e-12);
  EXPECT_LE(r.angle_left, start.q.angularDistance(target.q) + 1e-12);
  EXPECT_GE(r.angle_left, nearest - 1e-9);
  EXPECT_NE(r.message.find("nearest pose"), std::string::npos) << r.message;
  const WristBox at = WristBox::of(f.conjugate() * h.q);
  const WristBox local = nearest_in_box(f, target.q, at, 1e-3);
  EXPECT_GE(r.angle_left, (f * local.rotation()).angularDistance(target.q) - gap)
      << "a nearer allowed pose next to it: wrist at cone " << local.phi << ", twist " << local.t
      << " against " << at.phi << ", " << at.t;
  EXPECT_LE(r.angle_left, nearest + gap) << "the nearest allowed: " << nearest;
}

// Before (the turn's rows the sine of the tilt of the hand's z and the twist about it), a turn
// that tilted the hand's z past a right angle ended farther from its target than it began (2 rad
// about x: 2.2 rad left, the nearest allowed 0.87 away) and was called the nearest; 3 rad about
// x and y ended past the start too, and 8 turns ran the held solve to its stall rule (460-820
// iterations, no pose). The iterations: the held step's 10 and the origin's pull 1 included.
TEST(Reach, RobotArmHandTurnedAboutEachAxisStopsAtTheNearestPose) {
  for (const Vec3& axis : {Vec3(Vec3::UnitX()), Vec3(Vec3::UnitY())}) {
    for (double turn : {0.5, 1.0, 1.5, 2.0, 2.5, 3.0}) expect_robot_hand_turn(axis, turn, 40);
  }
  // About z the hand's x slides along the cone's rim, where the damped steps converged linearly
  // (2.5 rad: 81 iterations; 3 rad ran out of the turn's 80 steps 2.2e-5 rad short). With the
  // reduced steps (rim.hpp) 2.5 rad took 32 and 3 rad 76; within the drag step's 60 iterations
  // (drag.cpp's kStepIterations) 3 rad ran out of them 1.1e-6 rad short (56). With a turn's
  // steps cut short by the seed's turn made once and corrected once (pull.cpp: no step made
  // again for a bound it passed, kTurnCutShare), 2.5 rad takes 27 and 3 rad 53, to the nearest.
  for (double turn : {0.5, 1.0, 1.5, 2.0, 2.5}) expect_robot_hand_turn(Vec3::UnitZ(), turn, 40);
  expect_robot_hand_turn(Vec3::UnitZ(), 3.0, 60);
}

TEST(Reach, RobotArmHandTurnedAboutObliqueAxesStopsAtTheNearestPose) {
  for (double turn : {0.5, 1.0, 1.5, 2.0, 2.5, 3.0}) {
    expect_robot_hand_turn(Vec3(1, 1, 1), turn, 40);
    // Turned 2 rad about (0, 1, 1) the pull meets the twist's limit on its way, and the nearest
    // leaves it (0.954) along the cone's rim: held for good, the twist stopped the pull 4.8e-4 rad
    // short and that was called the nearest. The twist is let go when the step's impulse on its
    // row pushes it outward (pull.cpp's Holds); then the hand slides along the rim (64; 32 with
    // the reduced steps of rim.hpp).
    expect_robot_hand_turn(Vec3(0, 1, 1), turn, 40);
    // 3 rad about (1, -2, 0.5) ran out of the turn's steps 4.5e-7 rad short (95); with the
    // reduced steps it ended at the nearest pose after 56, then ran out of the drag step's 60
    // iterations (55, the turn's share); since the twelfth round it ends at the nearest after 42.
    expect_robot_hand_turn(Vec3(1, -2, 0.5), turn, turn < 3 ? 40 : 60);
  }
}

// A slider on a rod of the world (x in [-1, 1]) carries a bar of length 2 pinned at its origin,
// and `satellites` light bodies pinned there too (each three rows on the slider: with 50 the
// group has 160 rows, over the dense form's 120, and so many on one body that it is solved in
// the sparse saddle-point form). The bar's end (a hand pinned there) is pulled toward `target`
// by Session::pull. Started with the slider at `x0` and the bar along -x.
struct SliderBar {
  Model m;
  BodyId slider, bar, hand;
  JointId soft;
  SliderBar(int satellites, double x0, const Vec3& target) {
    auto body = [&](const std::string& name, const Vec3& at, double angle, double mass) {
      Body b;
      b.name = name;
      b.pose = Pose::from(at, Vec3(0, 0, angle));
      b.mass = mass;
      b.inertia = mass * Mat3::Identity();
      return m.add_body(b);
    };
    slider = body("slider", Vec3(x0, 0, 0), 0, 1);
    bar = body("bar", Vec3(x0, 0, 0), kPi, 1);
    hand = body("hand", Vec3(x0 - 2, 0, 0), 0, 1);
    Joint rod;
    rod.body2 = slider;
    rod.has_hinge = true;
    rod.guide = Guide{GuideKind::Axial, Vec3::UnitX(), -1, 1, 0, {}};
    m.add_joint(rod);
    m.add_joint(pin(slider, bar, Vec3::Zero()));
    m.add_joint(pin(bar, hand, Vec3(2, 0, 0)));
    for (int i = 0; i < satellites; ++i) {
      const BodyId s = body("s" + std::to_string(i), Vec3(x0, 0, 0), 0, 1e-3);
      m.add_joint(pin(slider, s, Vec3::Zero()));
    }
    soft = m.add_joint(pin(Model::kWorld, hand, target));
  }
};

// The nearest pose: the slider at the rod's point nearest the target's shadow, the bar stretched
// from it toward the target (distance |target - (clamp(x), 0, 0)| - 2). From the bar along -x
// the pull's steps take the slider past the rod's end, where the bound is held as rows; the
// nearest pose is inside, so the bound must be let go, which the rows' impulses tell. The same
// in the dense form (no satellites) and in the saddle-point form (50).
TEST(Reach, PullLetsGoOfABoundInTheSaddlePointForm) {
  const Vec3 target(0.3, 4, 0);
  for (int satellites : {0, 50}) {
    SCOPED_TRACE(satellites);
    SliderBar sb(satellites, 0.9, target);
    SolveOptions o;
    Session session(sb.m, o);
    std::vector<Pose> poses = sb.m.poses();
    const SolveResult r = session.pull(poses, sb.soft);
    ASSERT_EQ(r.status, SolveStatus::OutOfReach) << r.message;
    EXPECT_NEAR(r.distance_left, (target - Vec3(0.3, 0, 0)).norm() - 2, 1e-8);
    // (The distance is of second order in an error of the pose there, so the pose is known to the
    // root of the distance's precision.)
    EXPECT_NEAR(poses[static_cast<size_t>(sb.slider.value)].x.x(), 0.3, 1e-3);
    for (const ConstraintReport& c : measure(sb.m, poses, o)) {
      if (c.joint.value != sb.soft.value) EXPECT_TRUE(c.satisfied) << c.joint.value;
    }
  }
}

// The flying snake's s3 (samples/snake.dcl: its origin three links, 1.5, from the tail's end on
// the rod between x = -1 and 1) pulled toward (0, 10, 0) by Session::pull directly (the reach
// bound, which tells a drag at once, is not asked): the nearest pose has the tail's end at the
// rod's point under the target and the links stretched up from it, 10 - 1.5 = 8.5 away. The
// pull along the chain converges linearly; it stopped at a step gaining less than the tolerance,
// 8.5522 after 144 iterations, and called that the nearest.
TEST(Reach, SnakePulledAlongItsChainEndsAtTheNearestPoseOrSaysNot) {
  ParseResult parsed = load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/snake.dcl");
  ASSERT_TRUE(parsed.ok()) << parsed.messages();
  Model m = std::move(*parsed.model);
  ASSERT_TRUE(assemble(m).converged);
  const BodyId s3 = *m.find("s3"), tail = *m.find("tail");
  const Vec3 target(0, 10, 0);
  const JointId soft = m.add_joint(pin(Model::kWorld, s3, target));
  SolveOptions o;
  Session session(m, o);
  std::vector<Pose> poses = m.poses();
  const SolveResult r = session.pull(poses, soft);
  if (r.status == SolveStatus::OutOfReach) {
    EXPECT_NEAR(r.distance_left, 8.5, o.tolerance);
    EXPECT_NEAR(r.poses[static_cast<size_t>(tail.value)].x.x(), 0, 1e-4);
  } else {
    EXPECT_EQ(r.status, SolveStatus::IterationLimit) << r.message;
    EXPECT_GT(r.distance_left, 8.5);
  }
}

// The same pull cut off: with all_iterations (a drag step's turn: Dragger::turn, the step's 60)
// no iteration is made past it, the last correction back onto the joints included (made past
// the cap, it could add up to 6: 0-4 in the far-targets sweep), and the poses reached are
// valid and no farther from the target than the start (IterationLimit, no nearest claimed), for
// a cap at the bound itself or short of it.
TEST(Reach, PullCutOffMakesNoIterationPastAllIterations) {
  ParseResult parsed = load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/snake.dcl");
  ASSERT_TRUE(parsed.ok()) << parsed.messages();
  Model m = std::move(*parsed.model);
  ASSERT_TRUE(assemble(m).converged);
  const BodyId s3 = *m.find("s3");
  const Vec3 target(0, 10, 0);
  const JointId soft = m.add_joint(pin(Model::kWorld, s3, target));
  const SolveOptions o;
  const double began = (m.body(s3).pose.x - target).norm();
  for (int all : {3, 8, 20, 40}) {
    for (int reserve : {0, 2}) {
      SCOPED_TRACE(std::to_string(all) + " in all, " + std::to_string(reserve) + " reserved");
      Session session(m, o);
      std::vector<Pose> poses = m.poses();
      const std::vector<Pose> given = poses;
      const SolveResult r = session.pull(poses, soft, all - reserve, all);
      ASSERT_EQ(r.status, SolveStatus::IterationLimit) << r.message;
      EXPECT_LE(r.iterations, all);
      EXPECT_TRUE(same_bits(poses, given));  // not called the nearest: left as they were
      for (const ConstraintReport& c : measure(m, r.poses, o)) {
        if (c.joint.value != soft.value) EXPECT_TRUE(c.satisfied) << c.joint.value;
      }
      const double left = (r.poses[static_cast<size_t>(s3.value)].x - target).norm();
      EXPECT_NEAR(r.distance_left, left, 1e-9);
      EXPECT_LE(left, began + o.tolerance);
    }
  }
}

}  // namespace
}  // namespace dispcon
