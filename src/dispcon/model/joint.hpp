// A joint: one `constraint ... end` block of the description language (format.md).
//
// It composes at most one translation part (point to point, or a point of object2 guided by a
// set attached to object1: segment, ring/disc/plane, sphere/ball, circle, cylinder, polyline;
// seed 3 and 4.1) with optional rotation parts (angle, twist; seed 4.2). Points and vectors are in
// the local frame of the object they belong to; guides belong to object1.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "dispcon/math/rotation.hpp"
#include "dispcon/model/ids.hpp"

namespace dispcon {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

enum class GuideKind {
  Point,     // hinge only: P2 = P1 (seed 3, "point to point")
  Axial,     // P2 = P1 + lambda R1 u, lambda in [min, max] (seed 4.1.1)
  Planar,    // P2 in the plane (P1, R1 n), distance to P1 in [min, max] (seed 4.1.2)
  Sphere,    // |P2 - P1| in [min, max] (seed 4.1.3, "point in sphere")
  Circle,    // P2 on the circle (P1, R1 n, radius)   (seed 4.1.3, "point to curve")
  Cylinder,  // P2 on the cylinder (P1 + lambda R1 u, radius), lambda in [min, max] (4.1.3)
  Polyline,  // P2 on the polyline through `points` of object1 (4.1.3, a sampled curve)
};

const char* to_string(GuideKind kind);

struct Guide {
  GuideKind kind = GuideKind::Point;
  Vec3 dir = Vec3::UnitZ();  // u (axial, cylinder) or n (planar, circle), unit, object1's frame
  double min = -kInf;        // lambda (axial, cylinder) or distance (planar, sphere) lower bound
  double max = kInf;         // upper bound
  double radius = 0;         // circle, cylinder
  std::vector<Vec3> points;  // polyline vertices, object1's frame
};

// Angle between R1 a1 and R2 a2 kept in [min, max] within [0, pi] (seed 4.2.1).
struct AngleSpec {
  Vec3 a1 = Vec3::UnitZ();
  Vec3 a2 = Vec3::UnitZ();
  double min = 0;
  double max = kPi;
};

// Twist about h = normalise(R1 a1 + R2 a2): signed angle from b1' to b2' (R1 b1, R2 b2 projected
// on the plane perpendicular to h) kept in [min, max] within [-pi, pi] (seed 4.2.2, format.md).
struct TwistSpec {
  Vec3 b1 = Vec3::UnitX();
  Vec3 b2 = Vec3::UnitX();
  double min = 0;
  double max = 0;
};

// A coupling between the turns (or a turn and a travel) of the two objects (issue 11): gears,
// belts, rack and pinion, screw. The math of each is at the top of its part's file
// (parts/gear.hpp, rack_pinion.hpp, screw.hpp); every one holds
//   k1 theta1 + k2 theta2 + s = phase
// with theta the turns (unwrapped) and s a travel, so the state of a coupling is its phase alone.
enum class CouplingKind {
  Gear,   // turn2 = -ratio turn1, turns measured from the line of centres (external mesh)
  Belt,   // turn2 = +ratio turn1 (belt, chain, internal mesh)
  Rack,   // travel of object2 (the rack) along its axis = radius turn1 (object1: the pinion)
  Screw,  // travel of object2 along object1's axis = pitch / (2 pi) relative turn (right-handed)
};

const char* to_string(CouplingKind kind);

struct CouplingSpec {
  CouplingKind kind = CouplingKind::Gear;
  Vec3 c1 = Vec3::Zero();   // a point of object1's axis, object1's frame
  Vec3 a1 = Vec3::UnitZ();  // object1's axis, unit
  Vec3 c2 = Vec3::Zero();   // a point of object2's axis (rack: a point of the rack)
  Vec3 a2 = Vec3::UnitZ();  // object2's axis (rack: its direction of travel), unit
  double value = 1;         // ratio (gear, belt), radius (rack), pitch (screw); positive
  bool left = false;        // screw: left-handed
  // The coupling's constant; absent: taken at add_joint so that the model's poses hold it. The
  // model keeps it as the turns go round (Model::set_poses), so it survives full turns.
  std::optional<double> phase;
};

struct Joint {
  BodyId body1{0};  // the world (Model::kWorld) by default
  BodyId body2;

  bool has_hinge = false;
  Vec3 p1 = Vec3::Zero();  // local to body1
  Vec3 p2 = Vec3::Zero();  // local to body2
  std::optional<Guide> guide;

  std::optional<AngleSpec> angle;
  std::optional<TwistSpec> twist;  // requires angle
  std::optional<CouplingSpec> coupling;
  // Engine-internal, not in the format (nothing reads or writes it): object2's rotation held
  // equal to object1's, measured by the angle between them (parts/same_rotation.hpp). Only
  // Dragger::turn makes one, toward a drag's target rotation; no angle, twist or coupling with it.
  bool same_rotation = false;

  std::optional<double> move;  // mu12 in [0, 1]: body1's share of a translation
  double t0 = -kInf;           // active while t0 <= t <= t1
  double t1 = kInf;

  int line = 0;  // source line, 0 when built in code
  std::string label;

  // True when the block constrains translation: a hinge, a guide, or both.
  bool has_translation() const { return has_hinge || guide.has_value(); }
  bool active_at(double t) const { return t0 <= t && t <= t1; }
};

}  // namespace dispcon
