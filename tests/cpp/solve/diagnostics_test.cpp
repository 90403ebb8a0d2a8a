// Diagnostics on mechanisms of known mobility, on deliberately conflicting models, and the
// lock-up angles of a Grashof double-rocker against the analytic values.
#include "dispcon/solve/diagnostics.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/io/sweep_plot.hpp"
#include "dispcon/solve/rank.hpp"
#include "support/samples.hpp"

namespace dispcon {
namespace {

using test_support::sample;

std::vector<int> values(const std::vector<JointId>& ids) {
  std::vector<int> out;
  for (JointId j : ids) out.push_back(j.value);
  return out;
}

TEST(Check, KnownMobilities) {
  struct Expect {
    const char* file;
    int dof;
  };
  for (const Expect& e :
       {Expect{"fourbar.dcl", 1}, Expect{"bennett.dcl", 1}, Expect{"sarrus.dcl", 1},
        Expect{"peaucellier.dcl", 1}, Expect{"slider-crank.dcl", 1}, Expect{"welded.dcl", 0},
        Expect{"double-rocker.dcl", 1}}) {
    SCOPED_TRACE(e.file);
    const CheckResult c = check(sample(e.file));
    EXPECT_TRUE(c.solve.converged) << c.message;
    EXPECT_EQ(c.dof, e.dof) << c.message;
    EXPECT_TRUE(c.conflicting.empty());
  }
}

TEST(Check, PlanarFourBarIn3DHasThreeRedundantEquationsOnItsClosingJoint) {
  const Model m = sample("fourbar.dcl");
  const CheckResult c = check(m);
  EXPECT_EQ(c.dof, 1);
  EXPECT_EQ(values(c.redundant), std::vector<int>{3});
  ASSERT_EQ(c.advice.size(), 1u);
  EXPECT_NE(c.advice[0].find("3 of its 5 equations"), std::string::npos) << c.advice[0];
  const std::string line = "line " + std::to_string(m.joint(JointId{3}).line);
  EXPECT_NE(c.advice[0].find(line), std::string::npos) << c.advice[0];
  for (const char* body : {"crank", "coupler", "rocker"}) {
    EXPECT_EQ(c.body_dof[static_cast<size_t>(m.find(body)->value)], 1) << body;
  }
  // Its one line counts in words.
  EXPECT_EQ(c.message, "assembled; 1 degree of freedom, 1 redundant joint");
}

// The monocycle's line: plurals where there are several.
TEST(Check, MessageCountsInWords) {
  const CheckResult c = check(sample("monocycle.dcl"));
  ASSERT_EQ(c.redundant.size(), 1u);
  ASSERT_EQ(c.limits_active.size(), 4u);
  EXPECT_EQ(c.message, "assembled; 8 degrees of freedom, 1 redundant joint, 4 limits in contact");
}

// A four-bar whose base is welded to the world (a leg bolted to a frame): the base has no motion
// of its own, although its rows of the nullspace are rounding noise rather than zeros.
TEST(Check, APartWeldedInsideALoopHasNoMotion) {
  const ParseResult r = parse_dcl(R"(
object hip;     position 0 0 0.2;    rotation 0 0 0;    end
object crank;   position 0 0 0.2;    rotation 0 0 0.5;  end
object coupler; position 0.88 0.48 0.2; rotation 0 0 0.1; end
object rocker;  position 3 0 0.2;    rotation 0 0 1.9;  end
constraint object2 hip; hinge 0 0 0.2  0 0 0; angle 0 0 1 0 0 1 max 0; twist 1 0 0 1 0 0; end
constraint object1 hip;     object2 crank;   hinge 0 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 crank;   object2 coupler; hinge 1 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
constraint object1 coupler; object2 rocker;  hinge 3 0 0  2.5 0 0;  angle 0 0 1 0 0 1 max 0; end
constraint object1 hip;     object2 rocker;  hinge 3 0 0  0 0 0;    angle 0 0 1 0 0 1 max 0; end
)");
  ASSERT_TRUE(r.ok()) << r.messages();
  Model m = *r.model;
  ASSERT_TRUE(assemble(m).converged);
  const CheckResult c = check(m);
  EXPECT_EQ(c.dof, 1) << c.message;
  EXPECT_EQ(c.body_dof[static_cast<size_t>(m.find("hip")->value)], 0);
  for (const char* body : {"crank", "coupler", "rocker"}) {
    EXPECT_EQ(c.body_dof[static_cast<size_t>(m.find(body)->value)], 1) << body;
  }
}

Model chain(int n, bool revolute) {
  Model m;
  BodyId prev = Model::kWorld;
  for (int i = 0; i < n; ++i) {
    Body b;
    b.name = "link" + std::to_string(i);
    b.pose = Pose::from(Vec3(i, 0.1 * i, 0), Vec3(0, 0, 0.1 * i));
    const BodyId id = m.add_body(b);
    Joint j;
    j.body1 = prev;
    j.body2 = id;
    j.has_hinge = true;
    j.p1 = prev == Model::kWorld ? Vec3::Zero() : Vec3(1, 0, 0);
    if (revolute) j.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
    m.add_joint(j);
    prev = id;
  }
  return m;
}

TEST(Check, OpenChainsHaveTheirJointsFreedoms) {
  EXPECT_EQ(check(chain(5, true)).dof, 5);    // n revolutes: n
  EXPECT_EQ(check(chain(4, false)).dof, 12);  // n ball joints: 3 n
  const CheckResult c = check(chain(3, true));
  // The tip can move in all three ways (it follows every joint); the first link only turns.
  EXPECT_EQ(c.body_dof[1], 1);
  EXPECT_EQ(c.body_dof[3], 3);
}

TEST(Check, ConflictingJointIsNamedWithItsLine) {
  const CheckResult c = check(sample("conflicting.dcl"));
  EXPECT_FALSE(c.solve.converged);
  EXPECT_EQ(values(c.conflicting), std::vector<int>{4});
  bool named = false;
  for (const std::string& a : c.advice)
    named |= a.find("removing joint #4 (line 17)") != std::string::npos;
  EXPECT_TRUE(named);
  // The rest of the report is about the consistent model without it: the four-bar.
  EXPECT_EQ(c.dof, 1);
  EXPECT_EQ(values(c.redundant), std::vector<int>{3});
}

// Several samples side by side in one model, each its own group of bodies (names prefixed).
Model side_by_side(const std::vector<std::string>& files) {
  Model m;
  for (size_t k = 0; k < files.size(); ++k) {
    const Model part = sample(files[k]);
    std::vector<BodyId> id(static_cast<size_t>(part.body_count()), Model::kWorld);
    for (int i = 1; i < part.body_count(); ++i) {
      Body b = part.body(BodyId{i});
      b.name = "s" + std::to_string(k) + "_" + b.name;
      id[static_cast<size_t>(i)] = m.add_body(b);
    }
    for (const Joint& j : part.joints()) {
      Joint c = j;
      c.body1 = id[static_cast<size_t>(j.body1.value)];
      c.body2 = id[static_cast<size_t>(j.body2.value)];
      m.add_joint(c);
    }
  }
  return m;
}

TEST(Check, GroupByGroupGivesTheWholeJacobiansAnswers) {
  const std::vector<std::string> files = {
      "fourbar.dcl",     "bennett.dcl",      "sarrus.dcl",        "welded.dcl",
      "peaucellier.dcl", "slider-crank.dcl", "double-rocker.dcl", "robot-arm.dcl"};
  Model m = side_by_side(files);
  Body free_body;  // a group without joints
  free_body.name = "loose";
  m.add_body(free_body);
  ASSERT_TRUE(assemble(m).converged);
  const RankReport grouped = rank_by_group(m, {});
  const RankReport whole = rank_whole(m, {});
  EXPECT_EQ(grouped.dof, whole.dof);
  EXPECT_EQ(grouped.body_dof, whole.body_dof);
  ASSERT_EQ(grouped.redundant.size(), whole.redundant.size());
  for (size_t k = 0; k < whole.redundant.size(); ++k) {
    EXPECT_EQ(grouped.redundant[k].joint.value, whole.redundant[k].joint.value);
    EXPECT_EQ(grouped.redundant[k].equations, whole.redundant[k].equations);
    EXPECT_EQ(grouped.redundant[k].repeated, whole.redundant[k].repeated);
  }
  // And check() of the whole is the sum of its parts checked one by one.
  const CheckResult c = check(m);
  int dof = 6, redundant = 0;  // the loose body's six
  for (const std::string& f : files) {
    const CheckResult one = check(sample(f));
    dof += one.dof;
    redundant += static_cast<int>(one.redundant.size());
  }
  EXPECT_EQ(c.dof, dof);
  EXPECT_EQ(c.dof, whole.dof);
  EXPECT_EQ(static_cast<int>(c.redundant.size()), redundant);
  EXPECT_GT(redundant, 0);
  EXPECT_EQ(c.body_dof.back(), 6);
}

// A row of `cranks` parallelograms in the plane (gui_drag.py's chain): cranks of length 1 pinned
// 1.5 apart on the ground, each pair of neighbours joined by a coupler; the cranks' pins first,
// then each coupler's two pins. Every revolute is a hinge with its axes held parallel.
Model parallelogram_chain(int cranks) {
  std::string text;
  const auto num = [](double v) { return std::to_string(v); };
  for (int k = 0; k < cranks; ++k) {
    text += "object c" + std::to_string(k) + "; position " + num(1.5 * k) +
            " 0 0; rotation 0 0 1.0471975511965976; end\n";
  }
  for (int k = 0; k + 1 < cranks; ++k) {
    text += "object l" + std::to_string(k) + "; position " + num(1.5 * k + 0.5) +
            " 0.8660254037844386 0; end\n";
  }
  const std::string parallel = "; angle 0 0 1 0 0 1 max 0; end\n";
  for (int k = 0; k < cranks; ++k) {
    text += "constraint object2 c" + std::to_string(k) + "; hinge " + num(1.5 * k) + " 0 0  0 0 0" +
            parallel;
  }
  for (int k = 0; k + 1 < cranks; ++k) {
    const std::string l = " object2 l" + std::to_string(k) + ";";
    text += "constraint object1 c" + std::to_string(k) + ";" + l + " hinge 1 0 0  0 0 0" + parallel;
    text += "constraint object1 c" + std::to_string(k + 1) + ";" + l + " hinge 1 0 0  1.5 0 0" +
            parallel;
  }
  ParseResult r = parse_dcl(text);
  EXPECT_TRUE(r.ok()) << r.messages();
  return *r.model;
}

// A long chain (one group of 59 bodies, 88 joints): its redundant joints found without the SVD of
// every leading block of rows (which took minutes for the 100-part chain in FreeCAD), and they
// are the ones the geometry says: the pin that closes each parallelogram, 3 of its 5 equations
// repeating the planar loop's.
TEST(Check, ALongChainOfParallelogramsHasEachLoopsClosingPinRedundant) {
  const int cranks = 30;
  const CheckResult c = check(parallelogram_chain(cranks));
  ASSERT_TRUE(c.solve.converged) << c.message;
  EXPECT_EQ(c.dof, 1) << c.message;
  std::vector<int> closing;
  for (int k = 0; k + 1 < cranks; ++k) closing.push_back(cranks + 2 * k + 1);
  EXPECT_EQ(values(c.redundant), closing) << c.message;
  for (const std::string& a : c.advice) {
    EXPECT_NE(a.find("3 of its 5 equations"), std::string::npos) << a;
  }
  EXPECT_TRUE(c.conflicting.empty());
}

TEST(Check, AConflictInOneGroupIsFoundThere) {
  // The conflicting four-bar third of three: its joint 4 is joint 4 + 4 + 4 = 12 here.
  const Model m = side_by_side({"fourbar.dcl", "slider-crank.dcl", "conflicting.dcl"});
  ASSERT_EQ(m.joint(JointId{12}).body2, *m.find("s2_rocker"));
  const CheckResult c = check(m);
  EXPECT_FALSE(c.solve.converged);
  EXPECT_EQ(values(c.conflicting), std::vector<int>{12});
  // The rest is reported of the model without it: each linkage's closing joint redundant.
  EXPECT_EQ(c.dof, 3);
  EXPECT_EQ(values(c.redundant), (std::vector<int>{3, 7, 11}))
      << ::testing::PrintToString(values(c.redundant));
}

TEST(Check, ConflictsInTwoGroupsHaveNoSingleRemoval) {
  const CheckResult c = check(side_by_side({"conflicting.dcl", "fourbar.dcl", "conflicting.dcl"}));
  EXPECT_FALSE(c.solve.converged);
  std::vector<int> violated;
  for (JointId j : c.solve.violated()) violated.push_back(j.value);
  std::vector<int> conflicting = values(c.conflicting);
  std::sort(conflicting.begin(), conflicting.end());
  EXPECT_EQ(conflicting, violated);
  // Both groups' culprits are among them.
  EXPECT_NE(std::find(conflicting.begin(), conflicting.end(), 4), conflicting.end());
  EXPECT_NE(std::find(conflicting.begin(), conflicting.end(), 13), conflicting.end());
  bool said = false;
  for (const std::string& a : c.advice) said |= a.find("no single joint") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(Check, LimitsInContactAreListed) {
  const CheckResult c = check(sample("monocycle.dcl"));
  EXPECT_TRUE(c.solve.converged);
  EXPECT_FALSE(c.limits_active.empty());
  for (JointId j : c.limits_active)
    EXPECT_TRUE(c.solve.constraints[static_cast<size_t>(j.value)].at_limit);
}

TEST(Sweep, GrashofDoubleRockerLocksAtTheAnalyticAngles) {
  const Model m = sample("double-rocker.dcl");
  const double a = 2.5, b = 1, c = 2.8, d = 3;
  const double upper = std::acos((a * a + d * d - (b + c) * (b + c)) / (2 * a * d));
  const double lower = std::acos((a * a + d * d - (c - b) * (c - b)) / (2 * a * d));
  Model assembled = m;
  ASSERT_TRUE(assemble(assembled).converged);
  const Vec3 x = assembled.body(*m.find("input")).pose.q * Vec3::UnitX();
  const double start = std::atan2(x.y(), x.x());
  SweepOptions s;
  s.body = *m.find("input");
  s.steps = 60;
  s.from = 0;
  s.to = 1.5;
  const SweepResult up = sweep(m, s);
  ASSERT_TRUE(up.locked) << up.message;
  EXPECT_NEAR(start + up.lock_value, upper, 1e-6);
  s.to = -1.5;
  const SweepResult down = sweep(m, s);
  ASSERT_TRUE(down.locked) << down.message;
  EXPECT_NEAR(start + down.lock_value, lower, 1e-6);
  // Every other joint's value is reported at every sample, and the plot marks the lock.
  for (const SweepSample& x : up.samples) EXPECT_EQ(x.joint_values.size(), 4u);
  const std::string svg = write_sweep_svg(m, up);
  EXPECT_NE(svg.find("locks at"), std::string::npos);
  EXPECT_NE(svg.find("<polyline"), std::string::npos);
}

TEST(Sweep, BricardLoopMovesAlthoughGrueblerSaysItCannot) {
  const Model m = sample("bricard.dcl");
  SweepOptions s;
  s.body = *m.find("link2");
  s.axis = Vec3(0, -1, 0);  // joint 2's axis
  s.to = 0.5;
  s.steps = 25;
  s.solve.tolerance = 1e-10;
  const SweepResult r = sweep(m, s);
  ASSERT_FALSE(r.locked) << r.message;
  // The other links really move: link4's turn changes along the sweep.
  const SweepSample& first = r.samples.front();
  const SweepSample& last = r.samples.back();
  EXPECT_GT(last.poses[4].q.angularDistance(first.poses[4].q), 0.05);
  for (const SweepSample& x : r.samples) EXPECT_LT(x.max_residual, 1e-10);
}

TEST(Sweep, FullTurnOfACrankDoesNotLock) {
  SweepOptions s;
  const Model m = sample("fourbar.dcl");
  s.body = *m.find("crank");
  s.steps = 72;
  const SweepResult r = sweep(m, s);
  EXPECT_FALSE(r.locked) << r.message;
  EXPECT_EQ(r.samples.size(), 73u);
}

}  // namespace
}  // namespace dispcon
