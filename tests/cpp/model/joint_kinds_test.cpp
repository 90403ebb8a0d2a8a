// The joint vocabulary's tables: every row builds a joint the model accepts, that classifies back
// to its row, and that the .dcl writer and reader carry through unchanged.
#include "dispcon/model/joint_kinds.hpp"

#include <gtest/gtest.h>

#include <set>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/io/dcl_writer.hpp"
#include "dispcon/model/model.hpp"

namespace dispcon {
namespace {

// Limits and a curve that every kind accepts: just those its row takes.
JointLimits limits_for(const JointKindRow& row) {
  JointLimits l;
  if (row.limits & kTurnLimit) l.turn = Range{-0.5, 0.75};
  if (row.limits & kTravelLimit) l.travel = Range{-1, 2};
  if (row.limits & kConeLimit) l.cone = 0.4;
  if (row.limits & kAngleLimit) l.angle = Range{0.2, 0.3};
  if (row.limits & kDistanceLimit) l.distance = Range{1.5, 1.5};
  return l;
}

Model two_bodies() {
  Model m;
  Body a;
  a.name = "a";
  m.add_body(a);
  Body b;
  b.name = "b";
  m.add_body(b);
  return m;
}

const Anchor kAt1{Vec3(0.1, 0.2, 0.3), Vec3(0, 0, 2), Vec3(1, 0, 0)};
const Anchor kAt2{Vec3(-0.1, 0, 0.5), Vec3(0, 0, 1), Vec3(0, 3, 0)};
const std::vector<Vec3> kCurve{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)};

Joint build(const JointKindRow& row) {
  return make_joint(row.kind, BodyId{1}, kAt1, BodyId{2}, kAt2, limits_for(row),
                    row.needs_curve() ? kCurve : std::vector<Vec3>{});
}

TEST(JointKinds, EveryRowBuildsAJointThatClassifiesBackAndRoundTrips) {
  std::set<std::string> names;
  for (const JointKindRow& row : joint_kinds()) {
    SCOPED_TRACE(row.name);
    EXPECT_TRUE(names.insert(row.name).second) << "duplicate name";
    EXPECT_EQ(find_joint_kind(row.name), &row);
    Model m = two_bodies();
    const JointId id = m.add_joint(build(row));
    EXPECT_TRUE(m.warnings().empty());
    const Joint& j = m.joint(id);
    EXPECT_EQ(classify(j), row.kind);
    EXPECT_EQ(kind_name(j), row.name);
    // What the row says it composes is what the joint has.
    EXPECT_EQ(j.has_translation(), row.hinge);
    EXPECT_EQ(j.guide.has_value(), row.guide.has_value());
    if (row.guide) EXPECT_EQ(j.guide->kind, *row.guide);
    EXPECT_EQ(j.twist.has_value(), row.twist != TwistUse::None);
    const std::string text = write_dcl(m);
    EXPECT_NE(text.find("constraint  // " + std::string(row.name)), std::string::npos) << text;
    const ParseResult back = parse_dcl(text);
    ASSERT_TRUE(back.ok()) << back.messages() << text;
    EXPECT_EQ(classify(back.model->joint(JointId{0})), row.kind) << text;
    EXPECT_EQ(write_dcl(*back.model), text);
  }
  EXPECT_EQ(find_joint_kind("screw"), nullptr);
}

TEST(JointKinds, ConstructorsComposeTheDocumentedParts) {
  const BodyId w = Model::kWorld, b{1};
  const Joint rev = revolute(w, kAt1, b, kAt2);
  EXPECT_TRUE(rev.has_hinge);
  EXPECT_EQ(rev.p1, kAt1.point);
  EXPECT_EQ(rev.p2, kAt2.point);
  ASSERT_TRUE(rev.angle);
  EXPECT_EQ(rev.angle->min, 0);
  EXPECT_EQ(rev.angle->max, 0);
  EXPECT_FALSE(rev.twist);  // free turn
  const Joint limited = revolute(w, kAt1, b, kAt2, Range{-1, 1});
  ASSERT_TRUE(limited.twist);
  EXPECT_EQ(limited.twist->min, -1);
  EXPECT_EQ(limited.twist->b2, kAt2.across);

  const Joint sl = slider(w, kAt1, b, kAt2, Range{0, 5});
  ASSERT_TRUE(sl.guide);
  EXPECT_EQ(sl.guide->kind, GuideKind::Axial);
  EXPECT_EQ(sl.guide->dir, kAt1.axis);
  EXPECT_EQ(sl.guide->max, 5);
  ASSERT_TRUE(sl.twist);
  EXPECT_EQ(sl.twist->max, 0);  // welded turn

  const Joint loose = ball(w, kAt1, b, kAt2);
  EXPECT_FALSE(loose.angle);
  const Joint cone = ball(w, kAt1, b, kAt2, 0.5);
  ASSERT_TRUE(cone.angle);
  EXPECT_EQ(cone.angle->max, 0.5);

  const Joint perp = perpendicular(w, kAt1, b, kAt2);
  EXPECT_FALSE(perp.has_translation());
  EXPECT_EQ(perp.angle->min, kPi / 2);
  const Joint d = distance(w, kAt1, b, kAt2, Range{2, 2});
  EXPECT_EQ(d.guide->kind, GuideKind::Sphere);
  EXPECT_EQ(d.guide->min, 2);
  const Joint pc = point_on_curve(w, kCurve, b, kAt2);
  EXPECT_EQ(pc.guide->points, kCurve);
  EXPECT_EQ(point_on_plane(w, kAt1, b, kAt2).guide->min, 0);  // planar's default, not -inf
  EXPECT_EQ(planar_joint(w, kAt1, b, kAt2).guide->kind, GuideKind::Planar);
}

TEST(JointKinds, RefusesLimitsAKindDoesNotTakeAndMissingRequiredOnes) {
  JointLimits travel;
  travel.travel = Range{0, 1};
  EXPECT_THROW(make_joint(JointKind::Revolute, Model::kWorld, kAt1, BodyId{1}, kAt2, travel),
               std::invalid_argument);
  EXPECT_THROW(make_joint(JointKind::Angle, Model::kWorld, kAt1, BodyId{1}, kAt2),
               std::invalid_argument);
  EXPECT_THROW(make_joint(JointKind::Distance, Model::kWorld, kAt1, BodyId{1}, kAt2),
               std::invalid_argument);
  EXPECT_THROW(make_joint(JointKind::PointOnCurve, Model::kWorld, kAt1, BodyId{1}, kAt2),
               std::invalid_argument);
  EXPECT_THROW(make_joint(JointKind::Ball, Model::kWorld, kAt1, BodyId{1}, kAt2, {}, kCurve),
               std::invalid_argument);
}

TEST(JointKinds, ClassifyTellsSpecialCasesApart) {
  const BodyId w = Model::kWorld, b{1};
  // A revolute whose turn is held at zero is welded.
  EXPECT_EQ(classify(revolute(w, kAt1, b, kAt2, Range{0, 0})), JointKind::Fixed);
  EXPECT_EQ(classify(cylindrical(w, kAt1, b, kAt2, std::nullopt, Range{0, 0})), JointKind::Slider);
  // A ring (planar with a minimum distance) is no point on a plane.
  Joint ring = point_on_plane(w, kAt1, b, kAt2);
  ring.guide->min = 0.5;
  EXPECT_FALSE(classify(ring));
  EXPECT_EQ(kind_name(ring), "constraint");
  // An angle range of [0, 0] is the parallel row, which comes first.
  EXPECT_EQ(classify(angle_joint(w, kAt1, b, kAt2, Range{0, 0})), JointKind::Parallel);
}

TEST(Components, OneRowPerKeywordAndGuide) {
  std::set<std::string> keywords;
  for (const ComponentRow& row : components()) {
    EXPECT_TRUE(keywords.insert(row.keyword).second) << row.keyword;
    EXPECT_EQ(find_component(row.keyword), &row);
    EXPECT_EQ(&component(row.id), &row);
    if (row.guide) {
      EXPECT_EQ(&component(*row.guide), &row);
      EXPECT_STREQ(to_string(*row.guide), row.keyword);
    }
    if (row.has_bounds) {
      EXPECT_LE(row.natural.min, row.defaults.min) << row.keyword;
      EXPECT_GE(row.natural.max, row.defaults.max) << row.keyword;
    }
  }
  EXPECT_EQ(find_component("move"), nullptr);  // not geometry: the reader's own statement
}

TEST(Components, GetAndSetAreInverse) {
  Joint j;
  j.body2 = BodyId{1};
  for (const ComponentRow& row : components()) {
    SCOPED_TRACE(row.keyword);
    ComponentValues v;
    for (const ArgSpec& a : row.args) {
      if (a.kind == Arg::Point || a.kind == Arg::Direction) v.vectors.emplace_back(1, 2, 3);
      if (a.kind == Arg::PositiveLength || a.kind == Arg::NonNegativeLength) v.scalars.push_back(4);
      if (a.kind == Arg::Points) v.points = kCurve;
    }
    v.bounds = row.has_bounds ? Range{0.25, 0.5} : row.defaults;
    set_component(j, row.id, v);
    ASSERT_TRUE(has_component(j, row.id));
    const ComponentValues back = get_component(j, row.id);
    EXPECT_EQ(back.vectors, v.vectors);
    EXPECT_EQ(back.scalars, v.scalars);
    EXPECT_EQ(back.points, v.points);
    if (row.has_bounds) {
      EXPECT_EQ(back.bounds.min, 0.25);
      EXPECT_EQ(back.bounds.max, 0.5);
    }
  }
}

}  // namespace
}  // namespace dispcon
