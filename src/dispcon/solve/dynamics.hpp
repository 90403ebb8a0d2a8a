// The physics variant's animation (seed 2.2): 1. integrate each solid as if free (eqs. 1-4),
// 2. re-establish the constraints by displacement corrections (physics corrections conserve the
// first-order momenta), 3. correct the speeds from the positions actually reached.
#pragma once

#include <string>
#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {

struct AnimateOptions {
  double duration = 1.0;
  double dt = 0.01;                // frame step; sub-steps are taken when a rotation is too large
  Vec3 gravity = Vec3::Zero();     // added to every body with mass
  double max_step_rotation = 0.1;  // radians a body may turn in one integration step (seed 2.2)
  bool stop_on_violation = false;  // the seed's choice when the iteration cap is hit in a frame
  SolveOptions solve;              // step 2; its time is set to each frame's time
};

// The most frames an animation makes (duration / dt): each keeps every body's pose.
constexpr double kMaxFrames = 1e6;

// Throws std::invalid_argument (a ValueError naming the option) for a non-finite or out of range
// option, too many frames, or bad solve options.
void validate(const AnimateOptions& options);

struct Frame {
  double time = 0;
  int iterations = 0;
  double max_residual = 0;
  bool converged = true;
  bool diverged = false;          // a non-finite or out of range value: such a frame is not kept
  std::vector<JointId> violated;  // when not converged: the warning names these
  std::vector<Pose> poses;        // one per body
};

struct AnimateResult {
  bool converged = true;  // every frame converged
  bool stopped = false;   // stopped early (stop_on_violation, or a frame diverged)
  int iterations = 0;     // total
  double max_residual = 0;
  std::vector<Frame> frames;  // frame 0 is the start (after assembly)
  std::vector<std::string> warnings;
  std::string message;
};

// Animates from the model's poses and speeds (assembles first when the constraints do not hold),
// and leaves the model at the last frame with its speeds updated. A frame whose solve diverged
// (a non-finite or out of range value) stops the animation: it is not kept, and the model is left
// at the last good frame. Throws std::invalid_argument for bad options (validate()).
AnimateResult animate(Model& model, const AnimateOptions& options);

}  // namespace dispcon
