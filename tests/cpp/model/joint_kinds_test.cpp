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

// A rack's direction of travel lies across the pinion's axis.
const Anchor kRack{Vec3(0.5, -1, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};

// A coupling kind's value, given as its row says (a left-handed screw, to carry the flag).
CouplingValues coupling_for(const JointKindRow& row) {
  CouplingValues c;
  if (row.coupling) c.value = 0.75;
  if (row.coupling == CouplingKind::Screw) c.left = true;
  return c;
}

Joint build(const JointKindRow& row) {
  return make_joint(row.kind, BodyId{1}, kAt1, BodyId{2},
                    row.coupling == CouplingKind::Rack ? kRack : kAt2, limits_for(row),
                    row.needs_curve() ? kCurve : std::vector<Vec3>{}, coupling_for(row));
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
    ASSERT_EQ(j.coupling.has_value(), row.coupling.has_value());
    if (row.coupling) {
      EXPECT_EQ(j.coupling->kind, *row.coupling);
      EXPECT_EQ(j.coupling->value, 0.75);
      EXPECT_EQ(j.coupling->left, row.coupling == CouplingKind::Screw);
      EXPECT_TRUE(j.coupling->phase);  // taken at the poses: the writer writes it
    }
    const std::string text = write_dcl(m);
    EXPECT_NE(text.find("constraint  // " + std::string(row.name)), std::string::npos) << text;
    const ParseResult back = parse_dcl(text);
    ASSERT_TRUE(back.ok()) << back.messages() << text;
    EXPECT_EQ(classify(back.model->joint(JointId{0})), row.kind) << text;
    EXPECT_EQ(write_dcl(*back.model), text);
    if (row.coupling) {
      const CouplingSpec& x = *j.coupling;
      const CouplingSpec& y = *back.model->joint(JointId{0}).coupling;
      EXPECT_EQ(y.c1, x.c1);
      EXPECT_EQ(y.a1, x.a1);
      EXPECT_EQ(y.c2, x.c2);
      EXPECT_EQ(y.a2, x.a2);
      EXPECT_EQ(y.value, x.value);
      EXPECT_EQ(y.left, x.left);
      EXPECT_EQ(y.phase, x.phase);  // bit for bit: %.17g
    }
  }
  EXPECT_EQ(find_joint_kind("gearbox"), nullptr);
}

TEST(JointKinds, CouplingConstructorsPutTheAnchorsInTheirPlaces) {
  const BodyId w = Model::kWorld, b{1};
  const Joint g = gear(w, kAt1, b, kAt2, 2.5, 0.125);
  ASSERT_TRUE(g.coupling);
  EXPECT_EQ(g.coupling->kind, CouplingKind::Gear);
  EXPECT_EQ(g.coupling->c1, kAt1.point);
  EXPECT_EQ(g.coupling->a1, kAt1.axis);
  EXPECT_EQ(g.coupling->c2, kAt2.point);
  EXPECT_EQ(g.coupling->a2, kAt2.axis);
  EXPECT_EQ(g.coupling->value, 2.5);
  EXPECT_EQ(g.coupling->phase, 0.125);
  EXPECT_FALSE(g.has_translation());
  EXPECT_FALSE(g.angle);
  EXPECT_EQ(belt(w, kAt1, b, kAt2, 3).coupling->kind, CouplingKind::Belt);
  EXPECT_FALSE(belt(w, kAt1, b, kAt2, 3).coupling->phase);
  const Joint r = rack_pinion(w, kAt1, b, kRack, 0.3);
  EXPECT_EQ(r.coupling->kind, CouplingKind::Rack);
  EXPECT_EQ(r.coupling->c2, kRack.point);
  EXPECT_EQ(r.coupling->a2, kRack.axis);
  // A screw is a cylindrical pair plus its coupling.
  const Joint s = screw(w, kAt1, b, kAt2, 0.2, true);
  EXPECT_TRUE(s.has_hinge);
  ASSERT_TRUE(s.guide);
  EXPECT_EQ(s.guide->kind, GuideKind::Axial);
  ASSERT_TRUE(s.angle);
  EXPECT_EQ(s.angle->max, 0);
  EXPECT_FALSE(s.twist);
  EXPECT_TRUE(s.coupling->left);
  EXPECT_EQ(s.coupling->value, 0.2);
  // Without its coupling, a screw is a cylindrical joint; a gear alone is no named joint.
  Joint bare = s;
  bare.coupling.reset();
  EXPECT_EQ(classify(bare), JointKind::Cylindrical);
  EXPECT_EQ(classify(s), JointKind::Screw);
  EXPECT_STREQ(to_string(CouplingKind::Rack), "rack");
}

TEST(JointKinds, CouplingValuesGoOnlyWhereTheyBelong) {
  const BodyId w = Model::kWorld, b{1};
  auto message = [&](JointKind kind, const CouplingValues& c) {
    try {
      make_joint(kind, w, kAt1, b, kAt2, {}, {}, c);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message(JointKind::Gear, {}), "gear needs its ratio");
  EXPECT_EQ(message(JointKind::Rack, {}), "rack needs its radius");
  EXPECT_EQ(message(JointKind::Screw, {}), "screw needs its pitch");
  EXPECT_EQ(message(JointKind::Revolute, {2.0, false, std::nullopt}),
            "revolute is no coupling: it takes no ratio, radius, pitch or phase");
  EXPECT_EQ(message(JointKind::Belt, {2.0, true, std::nullopt}),
            "belt takes no left (only a screw is left- or right-handed)");
  // Values are the model's to check, at the argument they are about.
  Model m = two_bodies();
  try {
    m.add_joint(gear(w, kAt1, BodyId{1}, kAt2, -2));
    FAIL() << "a negative ratio was accepted";
  } catch (const JointError& e) {
    EXPECT_EQ(e.keyword(), "gear");
    EXPECT_EQ(e.arg(), "ratio");
    EXPECT_EQ(e.detail(), "gear ratio must be positive, found -2");
  }
  try {
    m.add_joint(gear(w, kAt1, BodyId{1}, Anchor{kAt2.point, Vec3::Zero(), kAt2.across}, 2));
    FAIL() << "a zero axis was accepted";
  } catch (const JointError& e) {
    EXPECT_EQ(e.arg(), "a2");
  }
  EXPECT_EQ(m.joint_count(), 0);
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
    EXPECT_TRUE(keywords.insert(std::string(row.keyword)).second) << row.keyword;
    EXPECT_EQ(find_component(row.keyword), &row);
    EXPECT_EQ(&component(row.id), &row);
    if (row.guide) {
      EXPECT_EQ(&component(*row.guide), &row);
      EXPECT_EQ(to_string(*row.guide), row.keyword);
    }
    if (row.coupling) {
      EXPECT_EQ(&component(*row.coupling), &row);
      EXPECT_EQ(to_string(*row.coupling), row.keyword);
      EXPECT_FALSE(row.guide);
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
      if (a.kind == Arg::PositiveLength || a.kind == Arg::NonNegativeLength ||
          a.kind == Arg::NamedPositive)
        v.scalars.push_back(4);
      if (a.kind == Arg::Points) v.points = kCurve;
      if (a.kind == Arg::Flag) v.flags.push_back(true);
      if (a.kind == Arg::NamedOption) v.options.emplace_back(0.5);
    }
    v.bounds = row.has_bounds ? Range{0.25, 0.5} : row.defaults;
    set_component(j, row.id, v);
    ASSERT_TRUE(has_component(j, row.id));
    const ComponentValues back = get_component(j, row.id);
    EXPECT_EQ(back.vectors, v.vectors);
    EXPECT_EQ(back.scalars, v.scalars);
    EXPECT_EQ(back.points, v.points);
    EXPECT_EQ(back.flags, v.flags);
    EXPECT_EQ(back.options, v.options);
    if (row.has_bounds) {
      EXPECT_EQ(back.bounds.min, 0.25);
      EXPECT_EQ(back.bounds.max, 0.5);
    }
  }
}

}  // namespace
}  // namespace dispcon
