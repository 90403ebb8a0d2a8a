// Dragging: one body held at a target (or along a path of targets) while the rest follows.
#include <algorithm>
#include <sstream>

#include "dispcon/solve/reach.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {

namespace {

std::vector<bool> held_only(const Model& model, BodyId body) {
  if (body.value <= 0 || body.value >= model.body_count()) {
    throw std::invalid_argument("drag: unknown body");
  }
  if (model.body(body).fixed) {
    throw std::invalid_argument("drag: object '" + model.body(body).name + "' is fixed");
  }
  std::vector<bool> held(static_cast<size_t>(model.body_count()), false);
  held[static_cast<size_t>(body.value)] = true;
  return held;
}

}  // namespace

Dragger::Dragger(Model& model, BodyId body, const SolveOptions& options)
    : model_(model),
      body_(body),
      options_(options),
      session_(model, options, held_only(model, body)) {}
Dragger::Dragger(Dragger&&) noexcept = default;
Dragger::~Dragger() = default;

SolveResult Dragger::move_to(const Pose& target) {
  const Pose at = check_pose(target, "target", "drag: target of '" + model_.body(body_).name + "'");
  // Out of reach by the joints' lengths: told now, not after the iterations give up (a
  // stretched chain's Newton steps crawl, and a thousand links took thousands of them).
  if (!reach_ || reach_->revision() != model_.revision()) {
    reach_ = std::make_unique<ReachBound>(model_, body_, options_.time);
  }
  if (reach_->gap(at, options_.tolerance).joint.value >= 0) return out_of_reach(at);
  poses_ = model_.poses();
  poses_[static_cast<size_t>(body_.value)] = at;
  SolveResult r = session_.solve(poses_);
  if (r.converged) model_.set_poses(poses_);
  return r;
}

// The step not tried: what is measured with the body at its target and the rest where it is (the
// joints on the stretched path are open), and the least distance left.
SolveResult Dragger::out_of_reach(const Pose& target) {
  const ReachBound::Gap gap = reach_->gap(target, options_.tolerance);
  SolveResult r;
  r.status = SolveStatus::OutOfReach;
  r.converged = false;
  r.poses = model_.poses();
  r.poses[static_cast<size_t>(body_.value)] = target;
  r.constraints = measure(model_, r.poses, options_);
  for (const ConstraintReport& c : r.constraints)
    r.max_residual = std::max(r.max_residual, c.residual);
  r.held = body_;
  r.distance_left = gap.distance;
  const Joint& j = model_.joint(gap.joint);
  std::ostringstream msg;
  msg << "out of reach: '" << model_.body(body_).name << "' stays at least " << gap.distance
      << " from its target (the " << gap.joints << " joint" << (gap.joints == 1 ? "" : "s")
      << " from joint " << gap.joint.value;
  if (j.line) msg << " (line " << j.line << ")";
  msg << " to a part that cannot move do not stretch that far)";
  r.message = msg.str();
  return r;
}

DragResult drag(Model& model, BodyId body, const Pose& target, int steps,
                const SolveOptions& options, std::vector<std::vector<Pose>>* step_poses) {
  if (steps < 1) throw ValueError("steps", "drag: steps must be at least 1");
  Dragger dragger(model, body, options);
  const Pose goal = check_pose(target, "target", "drag: target of '" + model.body(body).name + "'");
  const std::vector<Pose> given = model.poses();
  DragResult out;
  const SolveResult first = assemble(model, options);
  out.iterations = first.iterations;
  out.max_residual = first.max_residual;
  if (!first.converged) {
    out.converged = false;
    out.failed_step = 0;
    out.message = "the model does not assemble: " + first.message;
    return out;
  }
  const Pose start = model.body(body).pose;
  for (int k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    Pose p;
    p.x = (1 - t) * start.x + t * goal.x;
    p.q = start.q.slerp(t, goal.q).normalized();
    SolveResult r = dragger.move_to(p);
    out.iterations += r.iterations;
    out.max_residual = std::max(out.max_residual, r.max_residual);
    const bool ok = r.converged;
    out.steps.push_back(std::move(r));
    if (!ok) {
      out.converged = false;
      out.failed_step = k - 1;
      // No step was made: the assembly alone is not a drag, so nothing changes.
      if (k == 1) model.set_poses(given);
      break;
    }
    if (step_poses) step_poses->push_back(model.poses());
  }
  std::ostringstream msg;
  if (out.converged) {
    msg << "dragged '" << model.body(body).name << "' in " << steps << " steps, " << out.iterations
        << " iterations";
  } else {
    msg << "step " << out.failed_step + 1 << " of " << steps << " failed, '"
        << model.body(body).name << "' left "
        << (out.failed_step == 0 ? std::string("where it was")
                                 : "at step " + std::to_string(out.failed_step))
        << ": " << out.steps.back().message;
  }
  out.message = msg.str();
  return out;
}

}  // namespace dispcon
