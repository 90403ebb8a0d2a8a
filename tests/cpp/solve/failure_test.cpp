// A result never lies and a failure changes nothing: a failed solve, drag step or animation frame
// leaves every pose bit for bit as it was; a session follows the model's revision.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "dispcon/solve/diagnostics.hpp"
#include "dispcon/solve/dynamics.hpp"
#include "dispcon/solve/solver.hpp"
#include "support/samples.hpp"

namespace dispcon {
namespace {

using test_support::sample;

// The reproducer of issue 13: this one-step drag fails and used to leave link5 turned.
TEST(Failure, BricardFailedDragChangesNothing) {
  Model m = sample("bricard.dcl");
  const std::vector<Pose> before = m.poses();
  Pose target = m.body(*m.find("link2")).pose;
  target.x = Vec3(50, 50, 50);
  const DragResult d = drag(m, *m.find("link2"), target, 1);
  EXPECT_FALSE(d.converged);
  EXPECT_EQ(d.failed_step, 0);
  EXPECT_TRUE(same_bits(before, m.poses()));
}

// Property: over every sample, a drag to a random far target either converges (and then every
// joint holds as measure() sees it) or leaves the model bit for bit as it was.
TEST(Failure, FarDragsOverEverySampleChangeNothingOnFailure) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> far(-60, 60);
  int failures = 0;
  for (const char* name :
       {"bennett.dcl", "bricard.dcl", "conflicting.dcl", "double-rocker.dcl", "fourbar.dcl",
        "monocycle-push.dcl", "monocycle.dcl", "otary.dcl", "peaucellier.dcl", "robot-arm.dcl",
        "sarrus.dcl", "slider-crank.dcl", "snake.dcl", "welded.dcl"}) {
    Model m = sample(name);
    for (int b = 1; b < m.body_count(); ++b) {
      if (m.body(BodyId{b}).fixed) continue;
      SolveOptions o;
      o.max_iterations = 300;
      Pose target = m.body(BodyId{b}).pose;
      target.x += Vec3(far(rng), far(rng), far(rng));
      target.q = quat_from_rotation_vector(Vec3(far(rng), far(rng), far(rng)) / 20);
      const std::vector<Pose> before = m.poses();
      const DragResult d = drag(m, BodyId{b}, target, 1, o);
      if (d.converged) {
        for (const ConstraintReport& c : measure(m, m.poses(), o))
          EXPECT_LE(c.residual, o.tolerance) << name << " joint " << c.joint.value;
      } else {
        ++failures;
        EXPECT_TRUE(same_bits(before, m.poses())) << name << " body " << b;
      }
    }
  }
  EXPECT_GT(failures, 5);  // the property was exercised
}

TEST(Failure, ConvergedAtOnceKeepsTheBits) {
  Model m = sample("fourbar.dcl");
  ASSERT_TRUE(assemble(m).converged);
  const std::vector<Pose> assembled = m.poses();
  const SolveResult again = assemble(m);
  EXPECT_TRUE(again.converged);
  EXPECT_EQ(again.iterations, 0);
  EXPECT_TRUE(same_bits(assembled, m.poses()));
}

TEST(Failure, FailedAssemblyChangesNothing) {
  Model m = sample("conflicting.dcl");
  const std::vector<Pose> before = m.poses();
  SolveOptions o;
  o.max_iterations = 50;
  EXPECT_FALSE(assemble(m, o).converged);
  EXPECT_TRUE(same_bits(before, m.poses()));
}

// A session made before a joint was added rebuilds: it neither reads the old joints (freed when
// the vector grew) nor solves the old model.
TEST(Revision, SessionAndDraggerFollowTheModel) {
  Model m;
  const BodyId a = m.add_body(Body{"a"});
  Joint j;
  j.body2 = a;
  j.has_hinge = true;
  m.add_joint(j);
  Session session(m, SolveOptions{});
  Dragger dragger(m, a);
  const auto revision = m.revision();
  for (int k = 0; k < 40; ++k) {  // enough to move the joints' storage
    Joint more;
    more.body2 = a;
    more.has_hinge = true;
    more.p2 = Vec3(0, 0, 0);
    m.add_joint(more);
  }
  Joint far;
  far.body2 = a;
  far.has_hinge = true;
  far.p1 = Vec3(5, 0, 0);  // conflicts with the first hinge: a fresh solve cannot converge
  m.add_joint(far);
  EXPECT_GT(m.revision(), revision);
  std::vector<Pose> poses = m.poses();
  const SolveResult r = session.solve(poses);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.constraints.size(), static_cast<size_t>(m.joint_count()));
  EXPECT_FALSE(dragger.move_to(m.body(a).pose).converged);
}

TEST(Revision, ChangesThatSessionsBuildOnCount) {
  Model m;
  const BodyId a = m.add_body(Body{"a"});
  auto r = m.revision();
  m.set_fixed(a, true);
  EXPECT_GT(m.revision(), r);
  r = m.revision();
  m.set_pose(a, Pose::from(Vec3(1, 2, 3), Vec3::Zero()));
  EXPECT_EQ(m.revision(), r);  // poses are read afresh by every solve
}

// UBSan used to flag the check of a model whose only body is fixed (an empty Jacobian).
TEST(Failure, CheckOfOnlyFixedBodies) {
  Model m;
  Body b{"base"};
  b.fixed = true;
  m.add_body(b);
  const CheckResult r = check(m);
  EXPECT_EQ(r.dof, 0);
}

}  // namespace
}  // namespace dispcon
