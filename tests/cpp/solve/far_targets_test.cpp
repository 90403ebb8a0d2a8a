// Every sample's every movable body dragged toward targets far out of reach, in one step: a step
// that cannot be made is told within a few dozen iterations (issue 14: "an unreachable drag target
// recognised within a few dozen iterations, at any size"), leaves the model bit for bit as it
// was, and a nearest pose it reports is valid, measured as reported, and no farther from the
// target than the start. The sweep found the flying snake's 537-990 iterations (its links on a
// rod: reach.hpp); what it still finds is listed below, each with why.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "dispcon/solve/solver.hpp"
#include "support/samples.hpp"

namespace dispcon {
namespace {

// A few dozen: the most a step that cannot be made may take before it says so (the held solve's
// Newton steps, the pull, the turn: every iteration the step reports).
constexpr int kFewDozen = 60;

// The targets: the body's origin moved 50 along each axis (far beyond every sample's reach where
// the sample is tied to the world), and the body turned 2.5 rad about each axis with its origin
// where it is.
struct Far {
  const char* name;
  Vec3 move;
  Vec3 turn;
};
const Far kTargets[] = {
    {"+x", Vec3(50, 0, 0), Vec3::Zero()},  {"-x", Vec3(-50, 0, 0), Vec3::Zero()},
    {"+y", Vec3(0, 50, 0), Vec3::Zero()},  {"-y", Vec3(0, -50, 0), Vec3::Zero()},
    {"+z", Vec3(0, 0, 50), Vec3::Zero()},  {"-z", Vec3(0, 0, -50), Vec3::Zero()},
    {"rx", Vec3::Zero(), Vec3(2.5, 0, 0)}, {"ry", Vec3::Zero(), Vec3(0, 2.5, 0)},
    {"rz", Vec3::Zero(), Vec3(0, 0, 2.5)},
};

// Steps that still break a rule, by sample, body and target, with the rule they break: each is
// checked to still break it (a case that passes must leave the list). Not hidden: counted in
// docs/performance.md ("Issue 14, ninth round: far drags told sooner"; "Issue 14, tenth round:
// turns along a rim": 32 of 701 failing steps over 60 iterations, 35 before; "Issue 14, eleventh
// round: far targets": 30 of 699 -> 1; "Issue 14, twelfth round: far targets": 1 -> 0). The
// rules (with the status and iterations of a case when one is listed):
// - Farther: a turn whose nearest pose is farther from the target's rotation than the start. None
//   is listed since Dragger::turn measures the angle between the rotations (it measured a tilt by
//   its sine, which falls again past a right angle); the rule is still checked for every step.
// - Iterations: none is listed since the twelfth round. The otary's tail turned about x ran past
//   the turn's share of the step's 60 (drag.cpp's kStepIterations) by 4: its turn undid steps
//   whose corrected poses rose above the start at every t, each after a third point of the curve
//   of 6 corrections; a turn's curve search now stops at the second such point (pull.cpp), and
//   the step said iteration-limit after 55, at the same pose; with a turn's steps cut short by
//   the seed's turn made once and corrected once (pull.cpp, kTurnCutShare), after 54, 2.100001
//   rad left (2.105644 before).
// Since the eleventh round a drag step's turn gets what is left of the step's 60 iterations
// (less 6 for its last correction) instead of 80 of its own: the 24 turns that ran out of those
// 80 (83-101 in all) and the 3 that ended at the nearest pose after 65-77 say iteration-limit
// within 60, with the valid pose they reached; so do two that ended at it after 55 and 56 (the
// monocycle-push's left foot about z, the otary's head about x), now after 54, at the same pose
// to 2.4e-10 rad.
// Since the thirteenth round the turn's steps stop 2 short of the 60 (6 before) and its last
// correction is bounded by them (drag.cpp's kTurnReserve, Session::pull's all_iterations): no
// step can go over 60, and of the 32 turns that ran out of them none ends farther.
// Since the tenth round a turn that holds a bound takes reduced quasi-Newton steps on the
// directions the held rows leave free (rim.hpp, up to 5): the robot arm's hand about z (81 -> 32),
// the monocycle's body about x (85, out of its steps -> 32) and the monocycle-push's left foot
// about z (83 -> 55) left the list.
// (The otary's head turned about x, whose turn could not keep its joints, stalled after 98; its
// turn's pull no longer holds the bounds it met for good, and it is told within 60.)
// Since the ninth round none is the held solve's crawl or the pull's: a held solve whose Newton
// steps, cut short by the seed's turn, ask for more than a few dozen of them stops (two in a
// row), a linkage free to move as a whole is carried rigidly, and a pull that runs out of its 40
// steps is told as such (the otary's ball, the vice's jaw moved 50: its screw would turn 250
// times) instead of the held solve that persisted to its stall rule (493-5,893 iterations).
enum class Breaks { Iterations, Farther };
struct Known {
  const char* sample;
  const char* body;
  const char* target;
  Breaks rule;
};
const std::vector<Known> kKnown = {};

bool known(const std::string& sample, const std::string& body, const std::string& target,
           Breaks rule) {
  return std::any_of(std::begin(kKnown), std::end(kKnown), [&](const Known& k) {
    return k.sample == sample && k.body == body && k.target == target && k.rule == rule;
  });
}

std::vector<std::string> sample_names() {
  std::vector<std::string> names;
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(DISPCON_SOURCE_DIR) + "/samples")) {
    if (e.path().extension() == ".dcl") names.push_back(e.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

TEST(FarTargets, EverySamplesBodiesStopWithinAFewDozenIterations) {
  const SolveOptions o;
  std::set<std::string> skipped;
  std::set<std::tuple<std::string, std::string, std::string, int>> broken;
  int failed_steps = 0, out_of_reach = 0, bound_only = 0;
  const std::vector<std::string> names = sample_names();
  ASSERT_GE(names.size(), 20u);
  for (const std::string& name : names) {
    Model model = test_support::sample(name);
    if (!assemble(model, o).converged) {
      skipped.insert(name);
      continue;
    }
    for (int b = 1; b < model.body_count(); ++b) {
      const BodyId body{b};
      if (model.body(body).fixed) continue;
      const std::string body_name = model.body(body).name;
      for (const Far& far : kTargets) {
        SCOPED_TRACE(name + " " + body_name + " " + far.name);
        Model m = model;
        const std::vector<Pose> before = m.poses();
        const Pose start = m.body(body).pose;
        Pose target = start;
        target.x += far.move;
        target.q = (quat_from_rotation_vector(far.turn) * start.q).normalized();
        Dragger drag(m, body, o);
        const SolveResult r = drag.move_to(target);
        if (r.converged) {
          // Made: the body at its target, every joint holding.
          EXPECT_LT((m.body(body).pose.x - target.x).norm(), 1e-9);
          for (const ConstraintReport& c : measure(m, m.poses(), o)) EXPECT_TRUE(c.satisfied);
          continue;
        }
        ++failed_steps;
        // A failure changes nothing.
        EXPECT_TRUE(same_bits(before, m.poses()));
        auto rule = [&](Breaks which, bool holds, const std::string& what) {
          if (known(name, body_name, far.name, which)) {
            broken.insert({name, body_name, far.name, static_cast<int>(which)});
            EXPECT_FALSE(holds) << "listed as breaking it, but " << what
                                << " holds now: take it off kKnown";
          } else {
            EXPECT_TRUE(holds) << what << " (" << to_string(r.status) << ", " << r.iterations
                               << " iterations: " << r.message << ")";
          }
        };
        rule(Breaks::Iterations, r.iterations <= kFewDozen,
             "told within " + std::to_string(kFewDozen) + " iterations");
        if (r.status != SolveStatus::OutOfReach) continue;
        ++out_of_reach;
        ASSERT_EQ(r.poses.size(), before.size());
        const Pose& at = r.poses[static_cast<size_t>(b)];
        const double distance = (at.x - target.x).norm();
        if (distance == 0 && r.distance_left > o.tolerance) {
          // The reach bound alone (Dragger::move_to: the pull did not settle), said as such: the
          // poses are the model's with the body at its target, no nearest pose (distance_left is
          // how far a joint point of the body at its target stays beyond its path's reach).
          ++bound_only;
          EXPECT_NE(r.message.find("stays at least"), std::string::npos) << r.message;
          continue;
        }
        // The nearest pose: valid, measured as reported, and no farther than where it began.
        for (const ConstraintReport& c : measure(m, r.poses, o)) EXPECT_TRUE(c.satisfied);
        EXPECT_NEAR(r.distance_left, distance, 1e-6);
        bool nearer = distance <= (start.x - target.x).norm() + o.tolerance;
        if (r.angle_left > 0) {
          const double angle = at.q.angularDistance(target.q);
          EXPECT_NEAR(r.angle_left, angle, 1e-6);
          nearer = nearer && angle <= start.q.angularDistance(target.q) + o.tolerance;
        }
        rule(Breaks::Farther, nearer, "a nearest pose no farther from the target than the start");
      }
    }
  }
  // Only the sample meant not to assemble is left out (its joints conflict: samples/README.md).
  EXPECT_EQ(skipped, std::set<std::string>{"conflicting.dcl"});
  // Every listed case was met (a sample or body renamed would otherwise hide it).
  EXPECT_EQ(broken.size(), kKnown.size());
  // The sweep is exercised: most targets are out of reach.
  EXPECT_GT(failed_steps, 300);
  EXPECT_GT(out_of_reach, 250);
  std::printf("%d steps failed, %d out of reach, %d of them the bound alone\n", failed_steps,
              out_of_reach, bound_only);
}

// The vice's jaw moved 50 along its slide in one step: in reach, but only by turning the screw
// 250 times (pitch 0.2), 7,854 of the seed's 0.2 rad turns. The held solve stops after two Newton
// steps that ask for that many, and the pull runs out of its 40 steps still getting nearer: the
// step says so (IterationLimit, no nearest pose claimed) within a few dozen iterations, with the
// valid pose it reached. The screw turns at most 0.2 rad a Newton step, so the jaw cannot have
// travelled more than iterations x 0.2 x 0.2 / (2 pi). Moved 0.1 (half a turn), the step is
// made. (Before, moved 0.2 or more in one step, the held solve ended stalled, no pose, after
// 457-5,893 iterations.)
TEST(FarTargets, ViceJawMovedFarIsToldStillGettingNearer) {
  const SolveOptions o;
  Model m = test_support::sample("vice.dcl");
  ASSERT_TRUE(assemble(m, o).converged);
  const BodyId jaw = test_support::id(m, "jaw");
  const std::vector<Pose> before = m.poses();
  Pose target = m.body(jaw).pose;
  target.x.x() += 50;
  Dragger drag(m, jaw, o);
  const SolveResult r = drag.move_to(target);
  ASSERT_EQ(r.status, SolveStatus::IterationLimit) << r.message;
  EXPECT_LE(r.iterations, kFewDozen);
  EXPECT_TRUE(same_bits(before, m.poses()));
  EXPECT_NE(r.message.find("no nearest pose is claimed"), std::string::npos) << r.message;
  for (const ConstraintReport& c : measure(m, r.poses, o)) EXPECT_TRUE(c.satisfied);
  const double left = (r.poses[static_cast<size_t>(jaw.value)].x - target.x).norm();
  EXPECT_NEAR(r.distance_left, left, 1e-9);
  EXPECT_LT(left, 50);
  EXPECT_GE(left, 50 - r.iterations * 0.2 * 0.2 / (2 * kPi) - 1e-9);

  Pose near = m.body(jaw).pose;
  near.x.x() += 0.1;
  const SolveResult made = drag.move_to(near);
  ASSERT_TRUE(made.converged) << made.message;
  EXPECT_LT((m.body(jaw).pose.x - near.x).norm(), 1e-9);
  for (const ConstraintReport& c : measure(m, m.poses(), o)) EXPECT_TRUE(c.satisfied);
}

// The monocycle is free in space but for its body's tilt: its right thigh moved 50 down, which
// the held solve crawled toward and then ended stalled after 708 iterations, is made at once by
// carrying the whole monocycle with it: every body moved by the same 50, the rotations kept.
TEST(FarTargets, FreeLinkageIsCarriedAsOneBody) {
  const SolveOptions o;
  Model m = test_support::sample("monocycle.dcl");
  ASSERT_TRUE(assemble(m, o).converged);
  const BodyId thigh = test_support::id(m, "right-thigh");
  const std::vector<Pose> before = m.poses();
  const Vec3 move(0, -50, 0);
  Pose target = m.body(thigh).pose;
  target.x += move;
  Dragger drag(m, thigh, o);
  const SolveResult r = drag.move_to(target);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LE(r.iterations, kFewDozen);
  for (int b = 1; b < m.body_count(); ++b) {
    const Pose& p = m.body(BodyId{b}).pose;
    const Pose& was = before[static_cast<size_t>(b)];
    EXPECT_LT((p.x - (was.x + move)).norm(), 1e-12) << b;
    EXPECT_LT(p.q.angularDistance(was.q), 1e-12) << b;
  }
  for (const ConstraintReport& c : measure(m, m.poses(), o)) EXPECT_TRUE(c.satisfied);
}

}  // namespace
}  // namespace dispcon
