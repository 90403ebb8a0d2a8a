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

struct Joint {
  BodyId body1{0};  // the world (Model::kWorld) by default
  BodyId body2;

  bool has_hinge = false;
  Vec3 p1 = Vec3::Zero();  // local to body1
  Vec3 p2 = Vec3::Zero();  // local to body2
  std::optional<Guide> guide;

  std::optional<AngleSpec> angle;
  std::optional<TwistSpec> twist;  // requires angle

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
