// One model inside another: what `include "file" as NAME` does (format.md, "Sub-models").
//
// Let P be the placement (the sub-model's world to the model's world) and F the body the
// sub-model's world becomes (`on`, the world unless stated), so that a point x of the sub-model's
// world is T x in F's frame with T = pose(F)^-1 P.
// - Flexible (the default): every body b of the sub-model joins as NAME.b at pose P pose(b)
//   (speeds, force and torque turned by P); every joint joins as it is, except that its side on
//   the sub-model's world joins F, that side's points p -> T p and vectors v -> T v (a rigid change
//   of frame, which no component's equation can tell).
// - Rigid: the sub-model is assembled once, then its bodies are welded into one body NAME whose
//   frame is the sub-model's world, at pose P. The joints between its bodies hold by
//   construction and are dropped; a joint to its world joins NAME (that side carried by pose(b)
//   into NAME's frame) to F. Mass and inertia add up (parallel axes) when every body has them.
// A coupling's equation measures its turns from vectors the engine derives from each axis, so a
// change of frame shifts them by a constant: its phase moves by that shift, measured before and
// after, and the equation holds where it held.
#pragma once

#include <string>

#include "dispcon/model/model.hpp"

namespace dispcon {

struct Inclusion {
  std::string name;           // NAME: the prefix of the bodies, or the rigid body's name
  Pose placement;             // the sub-model's world in the model's world
  BodyId on = Model::kWorld;  // what the sub-model's world becomes
  bool rigid = false;
  int line = 0;  // the include statement's line: the joints' line, for reports
};

// Adds `sub` to `model` as `inc` says. Throws std::invalid_argument naming the problem (a name
// taken, a sub-model without objects, a rigid one that does not assemble); `model` may then hold
// part of it (the reader discards a model with errors).
void include_model(Model& model, const Model& sub, const Inclusion& inc);

}  // namespace dispcon
