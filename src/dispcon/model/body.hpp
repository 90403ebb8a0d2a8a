// A solid: its pose and the parameters that decide how it takes corrections.
//
// No-physics variant (seed 3.1.4): a scalar "ability to rotate" k replaces m J^-1.
// Physics variant (seed 3.1, eqs. 11-19): mass m and inertia tensor J about the centre of mass.
#pragma once

#include <optional>
#include <string>

#include "dispcon/math/rotation.hpp"

namespace dispcon {

struct Body {
  std::string name;
  int line = 0;  // source line in a .dcl file, 0 when built in code

  Pose pose;                   // local -> world
  Vec3 center = Vec3::Zero();  // centre of mass / of rotation, local
  bool fixed = false;

  std::optional<double> rotate;  // "ability to rotate" k > 0; derived when absent
  std::optional<double> mass;    // m > 0
  std::optional<Mat3> inertia;   // about `center`, local axes, symmetric positive definite

  // Physics variant only (seed 2.2): initial speeds and constant external actions, world frame.
  Vec3 velocity = Vec3::Zero();
  Vec3 spin = Vec3::Zero();
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();

  bool has_physics() const { return mass.has_value() && inertia.has_value(); }
  Vec3 world_center() const { return pose.apply(center); }
};

}  // namespace dispcon
