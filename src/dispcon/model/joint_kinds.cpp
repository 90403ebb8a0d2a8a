#include "dispcon/model/joint_kinds.hpp"

#include <stdexcept>
#include <string>

namespace dispcon {

namespace {

constexpr Range kAll{-kInf, kInf};
constexpr Range kDistances{0, kInf};
constexpr Range kAngles{0, kPi};
constexpr Range kTwists{-kPi, kPi};

// A coupling's statement: `C1 a1 C2 a2 VALUE v {left} {phase f}` (a rack: `C1 a1 P2 u ...`).
std::vector<ArgSpec> coupling_args(const char* value, bool left) {
  using A = Arg;
  const bool rack = std::string(value) == "radius";
  std::vector<ArgSpec> args{{A::Point, "C1"},
                            {A::Direction, "a1"},
                            {A::Point, rack ? "P2" : "C2", 2},
                            {A::Direction, rack ? "u" : "a2", 2},
                            {A::NamedPositive, value}};
  if (left) args.push_back({A::Flag, "left"});
  args.push_back({A::NamedOption, "phase"});
  return args;
}

std::vector<ComponentRow> make_components() {
  using A = Arg;
  return {
      {Component::Hinge,
       "hinge",
       "P1 of object1 and P2 of object2 meet (a guide moves P2 on it)",
       std::nullopt,
       {{A::Point, "P1"}, {A::Point, "P2", 2}},
       false,
       kAll,
       kAll,
       "",
       std::nullopt},
      {Component::Axial,
       "axial",
       "P2 on the line through P1 along R1 u (seed 4.1.1)",
       GuideKind::Axial,
       {{A::Direction, "u"}},
       true,
       kAll,
       kAll,
       "length",
       std::nullopt},
      {Component::Planar,
       "planar",
       "P2 on the plane through P1 of normal R1 n, at a distance from P1 within the bounds "
       "(seed 4.1.2)",
       GuideKind::Planar,
       {{A::Direction, "n"}},
       true,
       kDistances,
       kDistances,
       "length",
       std::nullopt},
      {Component::Sphere,
       "sphere",
       "P2 at a distance from P1 within the bounds (seed 4.1.3)",
       GuideKind::Sphere,
       {},
       true,
       kDistances,
       kDistances,
       "length",
       std::nullopt},
      {Component::Circle,
       "circle",
       "P2 on the circle of centre P1, normal R1 n, radius r (4.1.3)",
       GuideKind::Circle,
       {{A::Direction, "n"}, {A::PositiveLength, "r"}},
       false,
       kAll,
       kAll,
       "",
       std::nullopt},
      {Component::Cylinder,
       "cylinder",
       "P2 on the cylinder of axis P1 + lambda R1 u and radius r (seed 4.1.3)",
       GuideKind::Cylinder,
       {{A::Direction, "u"}, {A::NonNegativeLength, "r"}},
       true,
       kAll,
       kAll,
       "length",
       std::nullopt},
      {Component::Polyline,
       "polyline",
       "P2 on the polyline through these points of object1",
       GuideKind::Polyline,
       {{A::Points, "points"}},
       false,
       kAll,
       kAll,
       "",
       std::nullopt},
      {Component::Angle,
       "angle",
       "the angle between R1 a1 and R2 a2 within the bounds (4.2.1)",
       std::nullopt,
       {{A::Direction, "a1"}, {A::Direction, "a2", 2}},
       true,
       kAngles,
       kAngles,
       "radians",
       std::nullopt},
      {Component::Twist,
       "twist",
       "the turn from R1 b1 to R2 b2 about the angle's bisector within the bounds (4.2.2)",
       std::nullopt,
       {{A::Direction, "b1"}, {A::Direction, "b2", 2}},
       true,
       Range{0, 0},
       kTwists,
       "radians",
       std::nullopt},
      // The couplings (parts/gear.hpp, rack_pinion.hpp, screw.hpp): one equation between the
      // turns, or a turn and a travel, of the two objects.
      {Component::Gear, "gear",
       "object2's turn about a2 through C2 = -ratio times object1's about a1 through C1 (an "
       "external mesh), turns measured from the line of centres",
       std::nullopt, coupling_args("ratio", false), false, kAll, kAll, "", CouplingKind::Gear},
      {Component::Belt, "belt",
       "object2's turn about a2 through C2 = +ratio times object1's about a1 through C1 (a belt, "
       "a chain, an internal mesh)",
       std::nullopt, coupling_args("ratio", false), false, kAll, kAll, "", CouplingKind::Belt},
      {Component::Rack, "rack",
       "object2 (the rack, through P2) travels along u by radius times object1's turn about a1 "
       "through C1 (the pinion)",
       std::nullopt, coupling_args("radius", false), false, kAll, kAll, "", CouplingKind::Rack},
      {Component::Screw, "screw",
       "object2 travels along a1 by pitch / (2 pi) times its turn relative to object1 "
       "(right-handed unless `left`); with a cylindrical pair",
       std::nullopt, coupling_args("pitch", true), false, kAll, kAll, "", CouplingKind::Screw},
  };
}

std::vector<JointKindRow> make_joint_kinds() {
  using G = GuideKind;
  // Order matters to classify(): a row comes before any row it is a special case of.
  return {
      {JointKind::Fixed, "fixed", "Fixed",
       "no relative motion: the points meet, axes and turn held", true, std::nullopt,
       AngleUse::Fixed, 0, TwistUse::Weld, 0, std::nullopt},
      {JointKind::Revolute, "revolute", "Revolute", "turns about the common axis", true,
       std::nullopt, AngleUse::Fixed, 0, TwistUse::Turn, kTurnLimit, std::nullopt},
      {JointKind::Slider, "slider", "Slider", "slides along axis1 without turning", true, G::Axial,
       AngleUse::Fixed, 0, TwistUse::Weld, kTravelLimit, std::nullopt},
      {JointKind::Cylindrical, "cylindrical", "Cylindrical", "slides along and turns about axis1",
       true, G::Axial, AngleUse::Fixed, 0, TwistUse::Turn, kTravelLimit | kTurnLimit, std::nullopt},
      {JointKind::Ball, "ball", "Ball", "the points meet; any rotation (within a cone if given)",
       true, std::nullopt, AngleUse::Cone, 0, TwistUse::None, kConeLimit, std::nullopt},
      {JointKind::Planar, "planar", "Planar",
       "point2 on the plane of point1 and axis1, the axes parallel", true, G::Planar,
       AngleUse::Fixed, 0, TwistUse::None, 0, std::nullopt},
      {JointKind::PointOnLine, "point_on_line", "Point on line", "point2 on the line of axis1",
       true, G::Axial, AngleUse::None, 0, TwistUse::None, kTravelLimit, std::nullopt},
      {JointKind::PointOnPlane, "point_on_plane", "Point on plane",
       "point2 on the plane of point1 and axis1", true, G::Planar, AngleUse::None, 0,
       TwistUse::None, 0, std::nullopt},
      {JointKind::PointOnCurve, "point_on_curve", "Point on curve",
       "point2 on a curve of body1 (a polyline)", true, G::Polyline, AngleUse::None, 0,
       TwistUse::None, 0, std::nullopt},
      {JointKind::Parallel, "parallel", "Parallel", "the axes point the same way", false,
       std::nullopt, AngleUse::Fixed, 0, TwistUse::None, 0, std::nullopt},
      {JointKind::Perpendicular, "perpendicular", "Perpendicular", "the axes are perpendicular",
       false, std::nullopt, AngleUse::Fixed, kPi / 2, TwistUse::None, 0, std::nullopt},
      {JointKind::Angle, "angle", "Angle", "the angle between the axes within a range", false,
       std::nullopt, AngleUse::Range, 0, TwistUse::None, kAngleLimit, std::nullopt},
      {JointKind::Distance, "distance", "Distance", "the points at a distance within a range", true,
       G::Sphere, AngleUse::None, 0, TwistUse::None, kDistanceLimit, std::nullopt},
      {JointKind::Gear, "gear", "Gears",
       "body2 turns -ratio times body1 (external mesh; points and axes: the gears' centres and "
       "axes)",
       false, std::nullopt, AngleUse::None, 0, TwistUse::None, 0, CouplingKind::Gear},
      {JointKind::Belt, "belt", "Belt",
       "body2 turns +ratio times body1 (belt, chain, internal mesh)", false, std::nullopt,
       AngleUse::None, 0, TwistUse::None, 0, CouplingKind::Belt},
      {JointKind::Rack, "rack", "Rack and pinion",
       "body2 (the rack: point2, its direction axis2) travels radius times body1's turn", false,
       std::nullopt, AngleUse::None, 0, TwistUse::None, 0, CouplingKind::Rack},
      {JointKind::Screw, "screw", "Screw",
       "a cylindrical pair whose travel is pitch / (2 pi) times the turn", true, G::Axial,
       AngleUse::Fixed, 0, TwistUse::None, kTravelLimit, CouplingKind::Screw},
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

const ComponentRow* find_component(std::string_view keyword) {
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

const ComponentRow& component(CouplingKind kind) {
  for (const ComponentRow& r : components())
    if (r.coupling == kind) return r;
  throw std::logic_error("coupling kind missing from the table");
}

// The table's keywords are string literals: their views end where a NUL does.
const char* to_string(GuideKind kind) {
  return component(kind).keyword.data();
}

const char* to_string(CouplingKind kind) {
  return component(kind).keyword.data();
}

bool is_optional(Arg a) {
  return a == Arg::Flag || a == Arg::NamedOption;
}

bool has_component(const Joint& j, Component id) {
  return has_component(j, component(id));
}

bool has_component(const Joint& j, const ComponentRow& row) {
  switch (row.id) {
    case Component::Hinge:
      return j.has_hinge;
    case Component::Angle:
      return j.angle.has_value();
    case Component::Twist:
      return j.twist.has_value();
    case Component::Gear:
    case Component::Belt:
    case Component::Rack:
    case Component::Screw:
      return j.coupling && row.coupling == j.coupling->kind;
    default:
      return j.guide && row.guide == j.guide->kind;
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
    case Component::Gear:
    case Component::Belt:
    case Component::Rack:
    case Component::Screw: {
      const CouplingSpec& c = *j.coupling;
      v.vectors = {c.c1, c.a1, c.c2, c.a2};
      v.scalars = {c.value};
      if (id == Component::Screw) v.flags = {c.left};
      v.options = {c.phase};
      break;
    }
  }
  return v;
}

void set_component(Joint& j, Component id, const ComponentValues& v) {
  set_component(j, component(id), v);
}

void set_component(Joint& j, const ComponentRow& row, const ComponentValues& v) {
  const Component id = row.id;
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
    case Component::Gear:
    case Component::Belt:
    case Component::Rack:
    case Component::Screw: {
      CouplingSpec c;
      c.kind = *row.coupling;
      c.c1 = vec(0);
      c.a1 = vec(1);
      c.c2 = vec(2);
      c.a2 = vec(3);
      c.value = scalar(0);
      c.left = !v.flags.empty() && v.flags[0];
      c.phase = v.options.empty() ? std::nullopt : v.options[0];
      j.coupling = c;
      return;
    }
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
  return angle != AngleUse::None || guide == GuideKind::Axial || guide == GuideKind::Planar ||
         coupling.has_value();
}
bool JointKindRow::needs_across() const {
  return twist != TwistUse::None;
}
bool JointKindRow::needs_curve() const {
  return guide == GuideKind::Polyline;
}
bool JointKindRow::needs_points() const {
  return hinge || coupling.has_value();
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

namespace {

// A component's vectors and bounds, nothing else.
ComponentValues values(const decltype(ComponentValues::vectors)& vectors, Range bounds = {}) {
  ComponentValues v;
  v.vectors = vectors;
  v.bounds = bounds;
  return v;
}

}  // namespace

Joint make_joint(JointKind kind, BodyId body1, const Anchor& at1, BodyId body2, const Anchor& at2,
                 const JointLimits& limits, const std::vector<Vec3>& curve,
                 const CouplingValues& coupling) {
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
  const ComponentRow* coupled = row.coupling ? &component(*row.coupling) : nullptr;
  if (!coupled && (coupling.value || coupling.left || coupling.phase))
    throw std::invalid_argument(who + " is no coupling: it takes no ratio, radius, pitch or phase");
  if (coupled && !coupling.value)
    throw std::invalid_argument(who + " needs its " + std::string(coupled->args[4].name));
  if (coupling.left && row.coupling != CouplingKind::Screw)
    throw std::invalid_argument(who + " takes no left (only a screw is left- or right-handed)");

  Joint j;
  j.body1 = body1;
  j.body2 = body2;
  if (row.hinge) set_component(j, Component::Hinge, values({at1.point, at2.point}));
  if (row.guide) {
    const ComponentRow& c = component(*row.guide);
    ComponentValues g = values({at1.axis}, c.defaults);
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
  const decltype(ComponentValues::vectors) axes{at1.axis, at2.axis};
  switch (row.angle) {
    case AngleUse::None:
      break;
    case AngleUse::Fixed:
      set_component(j, Component::Angle, values(axes, {row.angle_value, row.angle_value}));
      break;
    case AngleUse::Cone:
      if (limits.cone) set_component(j, Component::Angle, values(axes, {0, *limits.cone}));
      break;
    case AngleUse::Range:
      if (!limits.angle) throw std::invalid_argument(who + " needs its angle range");
      set_component(j, Component::Angle, values(axes, *limits.angle));
      break;
  }
  const decltype(ComponentValues::vectors) across{at1.across, at2.across};
  switch (row.twist) {
    case TwistUse::None:
      break;
    case TwistUse::Weld:
      set_component(j, Component::Twist, values(across, {0, 0}));
      break;
    case TwistUse::Turn:
      if (limits.turn) set_component(j, Component::Twist, values(across, *limits.turn));
      break;
  }
  if (coupled) {
    ComponentValues v = values({at1.point, at1.axis, at2.point, at2.axis});
    v.scalars = {*coupling.value};
    v.flags = {coupling.left};
    v.options = {coupling.phase};
    set_component(j, coupled->id, v);
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

Joint gear(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, double ratio,
           std::optional<double> phase) {
  return make_joint(JointKind::Gear, b1, at1, b2, at2, {}, {}, {ratio, false, phase});
}
Joint belt(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, double ratio,
           std::optional<double> phase) {
  return make_joint(JointKind::Belt, b1, at1, b2, at2, {}, {}, {ratio, false, phase});
}
Joint rack_pinion(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, double radius,
                  std::optional<double> phase) {
  return make_joint(JointKind::Rack, b1, at1, b2, at2, {}, {}, {radius, false, phase});
}
Joint screw(BodyId b1, const Anchor& at1, BodyId b2, const Anchor& at2, double pitch, bool left,
            std::optional<double> phase) {
  return make_joint(JointKind::Screw, b1, at1, b2, at2, {}, {}, {pitch, left, phase});
}

std::optional<JointKind> classify(const Joint& j) {
  const std::optional<CouplingKind> coupling =
      j.coupling ? std::optional(j.coupling->kind) : std::nullopt;
  for (const JointKindRow& row : joint_kinds()) {
    if (coupling != row.coupling) continue;
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
