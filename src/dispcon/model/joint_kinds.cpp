#include "dispcon/model/joint_kinds.hpp"

#include <stdexcept>

namespace dispcon {

namespace {

constexpr Range kAll{-kInf, kInf};
constexpr Range kDistances{0, kInf};
constexpr Range kAngles{0, kPi};
constexpr Range kTwists{-kPi, kPi};

std::vector<ComponentRow> make_components() {
  using A = Arg;
  return {
      {Component::Hinge, "hinge", "P1 of object1 and P2 of object2 meet (a guide moves P2 on it)",
       std::nullopt, {{A::Point, "P1"}, {A::Point, "P2"}}, false, kAll, kAll, ""},
      {Component::Axial, "axial", "P2 on the line through P1 along R1 u (seed 4.1.1)",
       GuideKind::Axial, {{A::Direction, "u"}}, true, kAll, kAll, "length"},
      {Component::Planar, "planar",
       "P2 on the plane through P1 of normal R1 n, at a distance from P1 within the bounds "
       "(seed 4.1.2)",
       GuideKind::Planar, {{A::Direction, "n"}}, true, kDistances, kDistances, "length"},
      {Component::Sphere, "sphere", "P2 at a distance from P1 within the bounds (seed 4.1.3)",
       GuideKind::Sphere, {}, true, kDistances, kDistances, "length"},
      {Component::Circle, "circle", "P2 on the circle of centre P1, normal R1 n, radius r (4.1.3)",
       GuideKind::Circle, {{A::Direction, "n"}, {A::PositiveLength, "r"}}, false, kAll, kAll, ""},
      {Component::Cylinder, "cylinder",
       "P2 on the cylinder of axis P1 + lambda R1 u and radius r (seed 4.1.3)",
       GuideKind::Cylinder, {{A::Direction, "u"}, {A::NonNegativeLength, "r"}}, true, kAll, kAll,
       "length"},
      {Component::Polyline, "polyline", "P2 on the polyline through these points of object1",
       GuideKind::Polyline, {{A::Points, "points"}}, false, kAll, kAll, ""},
      {Component::Angle, "angle", "the angle between R1 a1 and R2 a2 within the bounds (4.2.1)",
       std::nullopt, {{A::Direction, "a1"}, {A::Direction, "a2"}}, true, kAngles, kAngles,
       "radians"},
      {Component::Twist, "twist",
       "the turn from R1 b1 to R2 b2 about the angle's bisector within the bounds (4.2.2)",
       std::nullopt, {{A::Direction, "b1"}, {A::Direction, "b2"}}, true, Range{0, 0}, kTwists,
       "radians"},
  };
}

std::vector<JointKindRow> make_joint_kinds() {
  using G = GuideKind;
  // Order matters to classify(): a row comes before any row it is a special case of.
  return {
      {JointKind::Fixed, "fixed", "Fixed", "no relative motion: the points meet, axes and turn held",
       true, std::nullopt, AngleUse::Fixed, 0, TwistUse::Weld, 0},
      {JointKind::Revolute, "revolute", "Revolute", "turns about the common axis",
       true, std::nullopt, AngleUse::Fixed, 0, TwistUse::Turn, kTurnLimit},
      {JointKind::Slider, "slider", "Slider", "slides along axis1 without turning",
       true, G::Axial, AngleUse::Fixed, 0, TwistUse::Weld, kTravelLimit},
      {JointKind::Cylindrical, "cylindrical", "Cylindrical", "slides along and turns about axis1",
       true, G::Axial, AngleUse::Fixed, 0, TwistUse::Turn, kTravelLimit | kTurnLimit},
      {JointKind::Ball, "ball", "Ball", "the points meet; any rotation (within a cone if given)",
       true, std::nullopt, AngleUse::Cone, 0, TwistUse::None, kConeLimit},
      {JointKind::Planar, "planar", "Planar",
       "point2 on the plane of point1 and axis1, the axes parallel", true, G::Planar,
       AngleUse::Fixed, 0, TwistUse::None, 0},
      {JointKind::PointOnLine, "point_on_line", "Point on line", "point2 on the line of axis1",
       true, G::Axial, AngleUse::None, 0, TwistUse::None, kTravelLimit},
      {JointKind::PointOnPlane, "point_on_plane", "Point on plane",
       "point2 on the plane of point1 and axis1", true, G::Planar, AngleUse::None, 0,
       TwistUse::None, 0},
      {JointKind::PointOnCurve, "point_on_curve", "Point on curve",
       "point2 on a curve of body1 (a polyline)", true, G::Polyline, AngleUse::None, 0,
       TwistUse::None, 0},
      {JointKind::Parallel, "parallel", "Parallel", "the axes point the same way", false,
       std::nullopt, AngleUse::Fixed, 0, TwistUse::None, 0},
      {JointKind::Perpendicular, "perpendicular", "Perpendicular", "the axes are perpendicular",
       false, std::nullopt, AngleUse::Fixed, kPi / 2, TwistUse::None, 0},
      {JointKind::Angle, "angle", "Angle", "the angle between the axes within a range", false,
       std::nullopt, AngleUse::Range, 0, TwistUse::None, kAngleLimit},
      {JointKind::Distance, "distance", "Distance", "the points at a distance within a range",
       true, G::Sphere, AngleUse::None, 0, TwistUse::None, kDistanceLimit},
  };
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Components

const std::vector<ComponentRow>& components() {
  static const std::vector<ComponentRow> rows = make_components();
  return rows;
}

const ComponentRow& component(Component id) {
  for (const ComponentRow& r : components())
    if (r.id == id) return r;
  throw std::logic_error("component missing from the table");
}

const ComponentRow* find_component(const std::string& keyword) {
  for (const ComponentRow& r : components())
    if (keyword == r.keyword) return &r;
  return nullptr;
}

const ComponentRow& component(GuideKind kind) {
  if (kind == GuideKind::Point) return component(Component::Hinge);
  for (const ComponentRow& r : components())
    if (r.guide == kind) return r;
  throw std::logic_error("guide kind missing from the table");
}

const char* to_string(GuideKind kind) {
  return component(kind).keyword;
}

bool has_component(const Joint& j, Component id) {
  switch (id) {
    case Component::Hinge:
      return j.has_hinge;
    case Component::Angle:
      return j.angle.has_value();
    case Component::Twist:
      return j.twist.has_value();
    default:
      return j.guide && component(id).guide == j.guide->kind;
  }
}

ComponentValues get_component(const Joint& j, Component id) {
  ComponentValues v;
  switch (id) {
    case Component::Hinge:
      v.vectors = {j.p1, j.p2};
      break;
    case Component::Angle:
      v.vectors = {j.angle->a1, j.angle->a2};
      v.bounds = {j.angle->min, j.angle->max};
      break;
    case Component::Twist:
      v.vectors = {j.twist->b1, j.twist->b2};
      v.bounds = {j.twist->min, j.twist->max};
      break;
    case Component::Polyline:
      v.points = j.guide->points;
      break;
    case Component::Sphere:
      v.bounds = {j.guide->min, j.guide->max};
      break;
    case Component::Circle:
      v.vectors = {j.guide->dir};
      v.scalars = {j.guide->radius};
      break;
    case Component::Cylinder:
      v.vectors = {j.guide->dir};
      v.scalars = {j.guide->radius};
      v.bounds = {j.guide->min, j.guide->max};
      break;
    case Component::Axial:
    case Component::Planar:
      v.vectors = {j.guide->dir};
      v.bounds = {j.guide->min, j.guide->max};
      break;
  }
  return v;
}

void set_component(Joint& j, Component id, const ComponentValues& v) {
  const ComponentRow& row = component(id);
  auto vec = [&](size_t k) { return k < v.vectors.size() ? v.vectors[k] : Vec3::Zero(); };
  auto scalar = [&](size_t k) { return k < v.scalars.size() ? v.scalars[k] : 0.0; };
  switch (id) {
    case Component::Hinge:
      j.has_hinge = true;
      j.p1 = vec(0);
      j.p2 = vec(1);
      return;
    case Component::Angle:
      j.angle = AngleSpec{vec(0), vec(1), v.bounds.min, v.bounds.max};
      return;
    case Component::Twist:
      j.twist = TwistSpec{vec(0), vec(1), v.bounds.min, v.bounds.max};
      return;
    default:
      break;
  }
  Guide g;
  g.kind = *row.guide;
  if (!v.vectors.empty()) g.dir = vec(0);
  g.radius = scalar(0);
  g.points = v.points;
  if (row.has_bounds) {
    g.min = v.bounds.min;
    g.max = v.bounds.max;
  }
  j.guide = g;
}

// ---------------------------------------------------------------------------------------------
// Joint kinds

bool JointKindRow::needs_axis() const {
  return angle != AngleUse::None || guide == GuideKind::Axial || guide == GuideKind::Planar;
}
bool JointKindRow::needs_across() const {
  return twist != TwistUse::None;
}
bool JointKindRow::needs_curve() const {
  return guide == GuideKind::Polyline;
}
bool JointKindRow::needs_points() const {
  return hinge;
}

const std::vector<JointKindRow>& joint_kinds() {
  static const std::vector<JointKindRow> rows = make_joint_kinds();
  return rows;
}

const JointKindRow& joint_kind(JointKind kind) {
  for (const JointKindRow& r : joint_kinds())
    if (r.kind == kind) return r;
  throw std::logic_error("joint kind missing from the table");
}

const JointKindRow* find_joint_kind(const std::string& name) {
  for (const JointKindRow& r : joint_kinds())
    if (name == r.name) return &r;
  return nullptr;
}

const char* to_string(JointKind kind) {
  return joint_kind(kind).name;
}

Joint make_joint(JointKind kind, BodyId body1, const Anchor& at1, BodyId body2, const Anchor& at2,
                 const JointLimits& limits, const std::vector<Vec3>& curve) {
  const JointKindRow& row = joint_kind(kind);
  const std::string who = row.name;
  auto refuse = [&](unsigned flag, bool given, const char* what) {
    if (given && !(row.limits & flag))
      throw std::invalid_argument(who + " takes no " + what + " limit");
  };
  refuse(kTurnLimit, limits.turn.has_value(), "turn");
  refuse(kTravelLimit, limits.travel.has_value(), "travel");
  refuse(kConeLimit, limits.cone.has_value(), "cone");
  refuse(kAngleLimit, limits.angle.has_value(), "angle");
  refuse(kDistanceLimit, limits.distance.has_value(), "distance");
  if (!row.needs_curve() && !curve.empty()) throw std::invalid_argument(who + " takes no curve");

  Joint j;
  j.body1 = body1;
  j.body2 = body2;
  if (row.hinge) set_component(j, Component::Hinge, {{at1.point, at2.point}, {}, {}, {}});
  if (row.guide) {
    const ComponentRow& c = component(*row.guide);
    ComponentValues g{{at1.axis}, {}, {}, c.defaults};
    switch (*row.guide) {
      case GuideKind::Axial:
        if (limits.travel) g.bounds = *limits.travel;
        break;
      case GuideKind::Sphere:
        if (!limits.distance) throw std::invalid_argument(who + " needs its distance");
        g.bounds = *limits.distance;
        break;
      case GuideKind::Polyline:
        if (curve.empty()) throw std::invalid_argument(who + " needs a curve (polyline points)");
        g.points = curve;
        break;
      default:
        break;
    }
    set_component(j, c.id, g);
  }
  const std::vector<Vec3> axes{at1.axis, at2.axis};
  switch (row.angle) {
    case AngleUse::None:
      break;
    case AngleUse::Fixed:
      set_component(j, Component::Angle, {axes, {}, {}, {row.angle_value, row.angle_value}});
      break;
    case AngleUse::Cone:
      if (limits.cone) set_component(j, Component::Angle, {axes, {}, {}, {0, *limits.cone}});
      break;
    case AngleUse::Range:
      if (!limits.angle) throw std::invalid_argument(who + " needs its angle range");
      set_component(j, Component::Angle, {axes, {}, {}, *limits.angle});
      break;
  }
  const std::vector<Vec3> across{at1.across, at2.across};
  switch (row.twist) {
    case TwistUse::None:
      break;
    case TwistUse::Weld:
      set_component(j, Component::Twist, {across, {}, {}, {0, 0}});
      break;
    case TwistUse::Turn:
      if (limits.turn) set_component(j, Component::Twist, {across, {}, {}, *limits.turn});
      break;
  }
  return j;
}

Joint fixed_joint(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2) {
  return make_joint(JointKind::Fixed, b1, at1, b2, at2);
}
Joint revolute(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2,
               std::optional<Range> turn) {
  JointLimits l;
  l.turn = turn;
  return make_joint(JointKind::Revolute, b1, at1, b2, at2, l);
}
Joint slider(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2,
             std::optional<Range> travel) {
  JointLimits l;
  l.travel = travel;
  return make_joint(JointKind::Slider, b1, at1, b2, at2, l);
}
Joint cylindrical(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2,
                  std::optional<Range> travel, std::optional<Range> turn) {
  JointLimits l;
  l.travel = travel;
  l.turn = turn;
  return make_joint(JointKind::Cylindrical, b1, at1, b2, at2, l);
}
Joint ball(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, std::optional<double> cone) {
  JointLimits l;
  l.cone = cone;
  return make_joint(JointKind::Ball, b1, at1, b2, at2, l);
}
Joint planar_joint(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2) {
  return make_joint(JointKind::Planar, b1, at1, b2, at2);
}
Joint point_on_line(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2,
                    std::optional<Range> travel) {
  JointLimits l;
  l.travel = travel;
  return make_joint(JointKind::PointOnLine, b1, at1, b2, at2, l);
}
Joint point_on_plane(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2) {
  return make_joint(JointKind::PointOnPlane, b1, at1, b2, at2);
}
Joint point_on_curve(BodyId b1, const std::vector<Vec3>& curve, BodyId b2, const Anchor& at2) {
  return make_joint(JointKind::PointOnCurve, b1, Anchor{}, b2, at2, {}, curve);
}
Joint parallel(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2) {
  return make_joint(JointKind::Parallel, b1, at1, b2, at2);
}
Joint perpendicular(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2) {
  return make_joint(JointKind::Perpendicular, b1, at1, b2, at2);
}
Joint angle_joint(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, Range angle) {
  JointLimits l;
  l.angle = angle;
  return make_joint(JointKind::Angle, b1, at1, b2, at2, l);
}
Joint distance(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, Range d) {
  JointLimits l;
  l.distance = d;
  return make_joint(JointKind::Distance, b1, at1, b2, at2, l);
}

std::optional<JointKind> classify(const Joint& j) {
  for (const JointKindRow& row : joint_kinds()) {
    if (j.has_translation() != row.hinge) continue;
    const std::optional<GuideKind> guide =
        j.guide && j.guide->kind != GuideKind::Point ? std::optional(j.guide->kind) : std::nullopt;
    if (guide != row.guide) continue;
    if (guide) {
      // A guide's bounds are the kind's limit (travel, distance) or must be the defaults: a
      // planar guide with a minimum distance is a ring, not a point on a plane.
      const bool limited = (row.limits & (kTravelLimit | kDistanceLimit)) != 0;
      const Range d = component(*guide).defaults;
      if (!limited && (j.guide->min != d.min || j.guide->max != d.max)) continue;
    }
    bool angle_ok = false;
    switch (row.angle) {
      case AngleUse::None:
        angle_ok = !j.angle;
        break;
      case AngleUse::Fixed:
        angle_ok = j.angle && j.angle->min == row.angle_value && j.angle->max == row.angle_value;
        break;
      case AngleUse::Cone:
        angle_ok = !j.angle || j.angle->min == 0;
        break;
      case AngleUse::Range:
        angle_ok = j.angle.has_value();
        break;
    }
    if (!angle_ok) continue;
    bool twist_ok = false;
    switch (row.twist) {
      case TwistUse::None:
        twist_ok = !j.twist;
        break;
      case TwistUse::Weld:
        twist_ok = j.twist && j.twist->min == 0 && j.twist->max == 0;
        break;
      case TwistUse::Turn:
        twist_ok = true;
        break;
    }
    if (twist_ok) return row.kind;
  }
  return std::nullopt;
}

std::string kind_name(const Joint& j) {
  const std::optional<JointKind> k = classify(j);
  return k ? to_string(*k) : "constraint";
}

}  // namespace dispcon
