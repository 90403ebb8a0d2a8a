// Model validation and derived parameters (format.md's defaults).
#include "dispcon/model/model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dispcon/model/bounds_error.hpp"

namespace dispcon {
namespace {

Body named(const std::string& name) {
  Body b;
  b.name = name;
  return b;
}

TEST(Model, WorldIsBodyZeroAndFixed) {
  Model m;
  EXPECT_EQ(m.body_count(), 1);
  EXPECT_EQ(m.body(Model::kWorld).name, "world");
  EXPECT_TRUE(m.body(Model::kWorld).fixed);
  EXPECT_EQ(m.find("world")->value, 0);
}

TEST(Model, RejectsBadBodies) {
  Model m;
  m.add_body(named("a"));
  EXPECT_THROW(m.add_body(named("a")), std::invalid_argument);
  EXPECT_THROW(m.add_body(named("world")), std::invalid_argument);
  Body heavy = named("heavy");
  heavy.mass = -1;
  EXPECT_THROW(m.add_body(heavy), std::invalid_argument);
  Body bad = named("bad");
  Mat3 J = Mat3::Identity();
  J(2, 2) = -1;
  bad.inertia = J;
  EXPECT_THROW(m.add_body(bad), std::invalid_argument);
  Body skewed = named("skewed");
  J = Mat3::Identity();
  J(0, 1) = 0.5;
  skewed.inertia = J;
  EXPECT_THROW(m.add_body(skewed), std::invalid_argument);
  // A refused body leaves nothing behind: its name is free, the model as it was.
  EXPECT_EQ(m.body_count(), 2);
  EXPECT_FALSE(m.find("heavy").has_value());
  heavy.mass = 2;
  const BodyId h = m.add_body(heavy);
  EXPECT_EQ(h.value, 2);
  EXPECT_EQ(m.find("heavy")->value, 2);
  EXPECT_EQ(m.body(h).name, "heavy");
}

TEST(Model, RejectsBadJoints) {
  Model m;
  const BodyId a = m.add_body(named("a"));
  Joint none;
  none.body2 = a;
  EXPECT_THROW(m.add_joint(none), std::invalid_argument);  // no component
  Joint self;
  self.body1 = a;
  self.body2 = a;
  self.has_hinge = true;
  EXPECT_THROW(m.add_joint(self), std::invalid_argument);
  Joint twist_alone;
  twist_alone.body2 = a;
  twist_alone.has_hinge = true;
  twist_alone.twist = TwistSpec{};
  EXPECT_THROW(m.add_joint(twist_alone), std::invalid_argument);
  Joint zero;
  zero.body2 = a;
  zero.angle = AngleSpec{Vec3::Zero(), Vec3::UnitZ(), 0, 0};
  EXPECT_THROW(m.add_joint(zero), std::invalid_argument);
  Joint inverted;
  inverted.body2 = a;
  inverted.guide = Guide{GuideKind::Axial, Vec3::UnitX(), 1.0, -1.0};
  EXPECT_THROW(m.add_joint(inverted), std::invalid_argument);
  Joint move;
  move.body2 = a;
  move.has_hinge = true;
  move.move = 1.5;
  EXPECT_THROW(m.add_joint(move), std::invalid_argument);
}

TEST(Model, NormalisesVectorsAndClampsAngleBounds) {
  Model m;
  Joint j;
  j.body2 = m.add_body(named("a"));
  j.angle = AngleSpec{Vec3(0, 0, 2), Vec3(3, 0, 0), 0, 9};  // Appendix A's `max 9`
  m.add_joint(j);
  EXPECT_NEAR(m.joint(JointId{0}).angle->a1.norm(), 1, 1e-15);
  EXPECT_DOUBLE_EQ(m.joint(JointId{0}).angle->max, kPi);
  // Not silently: the clamp is recorded, naming the statement, the value and the range.
  ASSERT_EQ(m.warnings().size(), 1u);
  EXPECT_EQ(m.warnings()[0].joint, JointId{0});
  EXPECT_EQ(m.warnings()[0].keyword, "angle");
  EXPECT_EQ(m.warnings()[0].message, "angle max 9 is outside [0, 3.14159]; clamped to 3.14159");
  // A refused joint records nothing.
  j.angle->min = 10;
  j.angle->max = 9;
  EXPECT_THROW(m.add_joint(j), JointError);
  EXPECT_EQ(m.warnings().size(), 1u);
}

TEST(Model, JointErrorsNameTheirStatement) {
  Model m;
  Joint j;
  j.body2 = m.add_body(named("a"));
  j.guide = Guide{GuideKind::Axial, Vec3::Zero()};
  try {
    m.add_joint(j);
    FAIL() << "accepted";
  } catch (const JointError& e) {
    EXPECT_EQ(e.keyword(), "axial");
    EXPECT_EQ(e.detail(), "axial u is a zero vector");
    EXPECT_EQ(std::string(e.what()), "constraint: axial u is a zero vector");
  }
  j.guide->dir = Vec3(1e200, 1e200, 0);  // scaled before the norm: no overflow
  const JointId id = m.add_joint(j);
  EXPECT_NEAR((m.joint(id).guide->dir - Vec3(1, 1, 0) / std::sqrt(2.0)).norm(), 0, 1e-15);
  j.guide->dir = Vec3(1e-320, 0, 0);  // subnormal, still a direction
  EXPECT_EQ(m.joint(m.add_joint(j)).guide->dir, Vec3(1, 0, 0));
  j.label = "\xFF";
  j.label[0] = static_cast<char>(0xFF);
  try {
    m.add_joint(j);
    FAIL() << "accepted";
  } catch (const JointError& e) {
    EXPECT_EQ(e.keyword(), "label");
  }
}

// Crossed bounds say what was refused, for a shell to say in its own words: the statement, the
// bounds as given and their unit; the message is the command line's.
TEST(Model, CrossedBoundsSayWhichBoundsAndTheirUnit) {
  Model m;
  Joint j;
  j.body2 = m.add_body(named("a"));
  j.has_hinge = true;
  j.angle = AngleSpec{Vec3(0, 0, 1), Vec3(0, 0, 1), 0, 0};
  j.twist = TwistSpec{Vec3(1, 0, 0), Vec3(1, 0, 0), 1.0472, 0.5};
  try {
    m.add_joint(j);
    FAIL() << "accepted";
  } catch (const BoundsError& e) {
    EXPECT_EQ(e.keyword(), "twist");
    EXPECT_EQ(e.min(), 1.0472);
    EXPECT_EQ(e.max(), 0.5);
    EXPECT_EQ(e.unit(), BoundsError::Unit::Angle);
    EXPECT_EQ(std::string(e.what()), "constraint: twist: min 1.0472 is above max 0.5");
  }
  j.twist.reset();
  j.has_hinge = false;
  j.angle.reset();
  j.guide = Guide{GuideKind::Axial, Vec3(0, 0, 1), 5, 2};
  try {
    m.add_joint(j);
    FAIL() << "accepted";
  } catch (const BoundsError& e) {
    EXPECT_EQ(e.keyword(), "axial");
    EXPECT_EQ(std::make_pair(e.min(), e.max()), std::make_pair(5.0, 2.0));
    EXPECT_EQ(e.unit(), BoundsError::Unit::Length);
  }
  EXPECT_EQ(m.joint_count(), 0);
}

TEST(Model, AbilityToRotateIsInverseSquaredRmsDistance) {
  Model m;
  Body b = named("bar");
  b.center = Vec3(1, 0, 0);
  const BodyId bar = m.add_body(b);
  const BodyId lone = m.add_body(named("lone"));
  Joint j1;
  j1.body2 = bar;
  j1.has_hinge = true;
  j1.p2 = Vec3(0, 0, 0);  // 1 from the centre
  Joint j2 = j1;
  j2.p2 = Vec3(4, 0, 0);  // 3 from the centre
  m.add_joint(j1);
  m.add_joint(j2);
  EXPECT_DOUBLE_EQ(m.ability_to_rotate(bar), 2.0 / (1.0 + 9.0));
  EXPECT_DOUBLE_EQ(m.ability_to_rotate(lone), 1.0);
  Body given = named("given");
  given.rotate = 0.25;
  EXPECT_DOUBLE_EQ(m.ability_to_rotate(m.add_body(given)), 0.25);
}

TEST(Model, MoveShareFollowsMassesAndFixedBodies) {
  Model m;
  Body a = named("a"), b = named("b");
  a.mass = 1;
  b.mass = 3;
  const BodyId ia = m.add_body(a), ib = m.add_body(b);
  Joint j;
  j.body1 = ia;
  j.body2 = ib;
  j.has_hinge = true;
  const JointId both = m.add_joint(j);
  EXPECT_DOUBLE_EQ(m.move_share(both), 0.75);  // m2 / (m1 + m2)
  j.move = 0.1;
  EXPECT_DOUBLE_EQ(m.move_share(m.add_joint(j)), 0.1);
  Joint w;
  w.body2 = ia;
  w.has_hinge = true;
  w.move = 0.9;
  EXPECT_DOUBLE_EQ(m.move_share(m.add_joint(w)), 0.0);  // the world takes nothing
}

}  // namespace
}  // namespace dispcon
