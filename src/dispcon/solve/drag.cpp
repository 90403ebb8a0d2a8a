// Dragging: one body held at a target (or along a path of targets) while the rest follows.
#include <algorithm>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <optional>
#include <sstream>

#include "dispcon/solve/reach.hpp"
#include "dispcon/solve/report.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {

namespace {

// Newton steps a drag step's pull may take before the held solve takes over (Dragger::pull).
constexpr int kPullIterations = 40;
// Iterations a drag step's turn may take (Dragger::turn), the held solve's and the origin's pull's
// included: what is left of a few dozen (issue 14: a target out of reach told within them, with
// how near the step got). Measured by the angle between the rotations, a turn against a ball
// joint's cone slides along the cone's rim (rim.hpp); where it has not settled by then it says
// so (IterationLimit, the valid pose it reached, no nearest claimed). Before, a turn had 80 of
// its own: the sweep's far targets (far_targets_test.cpp) took up to 101 in all, 24 of them
// still running out of those 80.
constexpr int kStepIterations = 60;
// Of those, what the turn's steps leave for the pull's last correction back onto the joints,
// made past their cap so that the poses it leaves are valid. The step's 60 bound that
// correction too (Session::pull's all_iterations): where it cannot make the joints hold within
// them, the turn ends at the last valid pose it kept. 6 before (the correction's most; 0-4
// used): 2 lets the far turns step on (the sweep's 32 turns out of their iterations nearer by
// 0.31 rad in all, none farther); at 1 the last correction met the step's end and a turn went
// back to an early valid pose (the monocycle-push's wheel about x: 0.58 -> 2.14 rad left).
constexpr int kTurnReserve = 2;

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

// The largest residual of a result's constraints (a NaN is passed over, as std::max does).
double largest_residual(const std::vector<ConstraintReport>& constraints) {
  double r = 0;
  for (const ConstraintReport& c : constraints) r = std::max(r, c.residual);
  return r;
}

// Adds the iterations each of `spent` took (in all, seed and polish) to `r`'s: a drag step
// reports every solve and pull it made.
void add_spent(SolveResult& r,
               std::initializer_list<std::reference_wrapper<const SolveResult>> spent) {
  for (const SolveResult& s : spent) {
    r.iterations += s.iterations;
    r.seed_iterations += s.seed_iterations;
    r.polish_iterations += s.polish_iterations;
  }
}

// The path a reach bound names, as its messages say it: "the N joints from joint J (line L)".
void describe_path(std::ostream& msg, const Model& model, const ReachBound::Gap& gap) {
  const Joint& j = model.joint(gap.joint);
  msg << "the " << gap.joints << " joint" << (gap.joints == 1 ? "" : "s") << " from joint "
      << gap.joint.value;
  if (j.line) msg << " (line " << j.line << ")";
}

// The model's poses with every body that `body` reaches through joints between movable bodies
// carried with it as one rigid body to `target` (ReachBound::carry, whose bodies joined are the
// same), when every active joint holds there (those to the world and to fixed bodies included: a
// linkage free in space, or on a plane moved along it), measured as reported: then a step to
// `target` is made at once. Else nullopt.
std::optional<SolveResult> carried(const Model& model, const ReachBound& reach, BodyId body,
                                   const Pose& target, const SolveOptions& options) {
  const std::vector<Pose> poses = model.poses();
  SolveResult r;
  r.poses = poses;
  r.poses[static_cast<size_t>(body.value)] = target;
  std::vector<int> moved_with(poses.size(), -1);
  moved_with[static_cast<size_t>(body.value)] = body.value;
  if (!reach.carry(model, poses, r.poses, moved_with, options, r.constraints)) return std::nullopt;
  for (const Pose& p : r.poses) {
    if (!(p.x.cwiseAbs().maxCoeff() <= kLargest)) return std::nullopt;  // off the model's range
  }
  r.max_residual = largest_residual(r.constraints);
  return r;
}

}  // namespace

Puller::Puller(Model& model, BodyId body, const Vec3& point, const SolveOptions& options)
    : model_(model),
      body_(body),
      point_(check_vector(point, "point", "pull: point of '" + model.body(body).name + "'")),
      options_(options) {
  held_only(model, body);  // the same door as a drag's
  validate(options);
}
Puller::Puller(Puller&&) noexcept = default;
Puller::~Puller() = default;

SolveResult Puller::pull_to(const Vec3& target, bool move) {
  const Vec3 at =
      check_vector(target, "target", "pull: target of '" + model_.body(body_).name + "'");
  if (!session_ || revision_ != model_.revision()) {
    // The model and a joint from the target to the point, solved by a session of its own: the
    // model itself is not touched (its revision, its other sessions).
    pulled_ = model_;
    Joint j;
    j.body2 = body_;
    j.has_hinge = true;
    j.p2 = point_;
    j.label = "pull";
    joint_ = pulled_.add_joint(j);
    session_ = std::make_unique<Session>(pulled_, options_);
    revision_ = model_.revision();
  }
  // Beyond what a path of point-to-point joints stretches to: the path stretched toward the
  // target is the nearest pose there is, when it breaks no joint (reach.hpp).
  if (!reach_ || reach_->revision() != model_.revision()) {
    reach_ = std::make_unique<ReachBound>(model_, body_, options_.time);
  }
  std::vector<Pose> poses = model_.poses();
  std::optional<ReachBound::Stretch> stretched =
      reach_->stretch(model_, poses, point_, at, options_);
  if (stretched) {
    SolveResult r;
    r.status = SolveStatus::OutOfReach;
    r.converged = false;
    r.poses = std::move(stretched->poses);
    r.constraints = std::move(stretched->constraints);
    r.max_residual = largest_residual(r.constraints);
    r.held = body_;
    r.distance_left = stretched->distance;
    std::ostringstream msg;
    msg << "out of reach: '" << model_.body(body_).name << "' stays " << r.distance_left
        << " from its target at the nearest pose its joints allow (";
    describe_path(msg, model_, stretched->gap);
    msg << " to a part that cannot move, stretched toward it)";
    r.message = msg.str();
    if (move) model_.set_poses(r.poses);
    return r;
  }
  pulled_.set_hinge(joint_, at, std::nullopt);
  SolveResult r = session_->pull(poses, joint_);
  // Reported as the model's joints: the pull's own is the last.
  r.constraints.pop_back();
  r.max_residual = largest_residual(r.constraints);
  r.held = body_;
  const bool holds =
      r.status != SolveStatus::Diverged && r.status != SolveStatus::Stalled && r.violated().empty();
  if (!holds) r.distance_left = 0;
  std::ostringstream msg;
  if (r.status == SolveStatus::OutOfReach) {
    msg << "out of reach: '" << model_.body(body_).name << "' stays " << r.distance_left
        << " from its target at the nearest pose its joints allow";
    r.message = msg.str();
  } else if (!holds) {
    r.message = "pull: " + r.message;
  }
  if (move && holds) model_.set_poses(r.poses);
  return r;
}

// A step whose target the held body's origin can reach but whose rotation it cannot: the model
// with a fixed ghost of the held body at the target and two joints from it to the held body,
// the origin held there (hard) and the rotation matched (the pull's soft joint). The ghost's
// pose is the target's, given with the poses at each pull: the session is built once.
struct Dragger::Turn {
  Model model;
  BodyId ghost{-1};
  JointId rotation{-1};
  std::uint64_t revision = 0;  // the dragged model's when this was made
  std::unique_ptr<Session> session;

  Turn(const Model& dragged, BodyId body, const SolveOptions& options)
      : model(dragged), revision(dragged.revision()) {
    Body g;
    g.name = "target";
    while (model.find(g.name)) g.name += "_";
    g.fixed = true;
    g.pose = dragged.body(body).pose;
    ghost = model.add_body(g);
    Joint origin;
    origin.body1 = ghost;
    origin.body2 = body;
    origin.has_hinge = true;
    origin.label = "target origin";
    model.add_joint(origin);
    Joint turn;
    turn.body1 = ghost;
    turn.body2 = body;
    turn.same_rotation = true;
    turn.label = "target rotation";
    rotation = model.add_joint(turn);
    session = std::make_unique<Session>(model, options);
  }
};

Dragger::Dragger(Model& model, BodyId body, const SolveOptions& options)
    : model_(model),
      body_(body),
      options_(options),
      session_(model, options, held_only(model, body), Session::Stuck::StopWhenSlow) {}
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
  if (r.converged) {
    model_.set_poses(poses_);
    return r;
  }
  if (r.status == SolveStatus::Diverged) return r;
  // A linkage free to move as a whole (in space, on a plane): carried rigidly with the held
  // body, every joint may still hold; then the step is made at once, where the held Newton
  // steps, cut short by the seed's turn, crawl (the monocycle's thigh moved 50: 400-2,000
  // iterations).
  if (std::optional<SolveResult> made = carried(model_, *reach_, body_, at, options_)) {
    add_spent(*made, {r});
    made->message = solve_message(model_, *made) + ": carried with '" + model_.body(body_).name +
                    "' as one rigid body";
    model_.set_poses(made->poses);
    return std::move(*made);
  }
  // Near a path's full stretch Newton steps crawl (the first-order model sees almost no way to
  // change the path's reach); the path straightened by the factor that meets the target
  // (ReachBound::straighten) is a valid pose from which the held solve has nothing or little left.
  std::optional<std::vector<Pose>> straight =
      reach_->straighten(model_, model_.poses(), at, options_);
  // The held solve as it was before the slow rule (kept for what follows it), so that a
  // reachable step's pose is the one it always was.
  auto patient = [this](std::vector<Pose>& poses) {
    session_.set_stuck(Session::Stuck::Stop);
    SolveResult p = session_.solve(poses);
    session_.set_stuck(Session::Stuck::StopWhenSlow);
    return p;
  };
  // That held solve from the straightened path: true when it made the step (then `r`).
  auto from_straight = [&]() {
    if (!straight) return false;
    poses_ = std::move(*straight);
    straight.reset();
    SolveResult s = patient(poses_);
    if (s.converged) {
      model_.set_poses(poses_);
      add_spent(s, {r});
      r = std::move(s);
      return true;
    }
    add_spent(r, {s});
    return false;
  };
  // A step whose Newton steps ask for more turns than a few dozen steps of the seed's 0.2 rad
  // make (Session::far): the held solve would crawl toward it for hundreds or thousands of
  // steps, whether it is in reach or not. The pull tells which within its 40 (the straightened
  // path first, near a full stretch).
  if (session_.far()) {
    if (from_straight()) return r;
    return pull(at, std::move(r), std::nullopt);
  }
  std::optional<SolveResult> near;
  if (session_.slowed()) {
    // Whole Newton steps that do not halve the violation: the joints settle on a misfit, as
    // where the target is out of reach, and the pull tells that sooner than the held steps would
    // give up (a four-bar held past its dead point: 5 held steps instead of 11). Not near a
    // path's full stretch, where they crawl toward a target in reach.
    std::optional<SolveResult> told;
    if (!straight) {
      near = puller().pull_to(at.x, false);
      told = fall_back(at, r, *near);
      if (told && !told->converged) return std::move(*told);
    }
    // Reachable after all (the turn got there), or not told: the held solve without that rule,
    // so that a reachable step's pose is the one it always was.
    poses_ = model_.poses();
    poses_[static_cast<size_t>(body_.value)] = at;
    SolveResult p = patient(poses_);
    if (told && !p.converged && p.status != SolveStatus::Diverged) {
      // The turn's pose: the held body at its target, every joint holding.
      add_spent(*told, {p});
      model_.set_poses(told->poses);
      return std::move(*told);
    }
    if (told) {
      add_spent(p, {*told});
    } else {
      add_spent(p, {r});
      if (near) add_spent(p, {*near});
    }
    if (p.converged) {
      model_.set_poses(poses_);
      return p;
    }
    if (p.status == SolveStatus::Diverged) return p;
    r = std::move(p);
    if (near) near->iterations = near->seed_iterations = near->polish_iterations = 0;  // in `r`
  }
  if (from_straight()) return r;
  return pull(at, std::move(r), std::move(near));
}

// The held step's Newton steps failed: the body's origin is pulled toward the target's from the
// model's poses (`pulled`: that pull when made already), and what the pull and the turn tell is
// the step's answer (fall_back), the turn's pose when it got there. Only where the pull could not
// keep the joints does the held solve that persists (seed iterations between Newton's, the stall
// rule) make the step from where it began.
SolveResult Dragger::pull(const Pose& target, SolveResult held, std::optional<SolveResult> pulled) {
  SolveResult near = pulled ? std::move(*pulled) : puller().pull_to(target.x, false);
  if (std::optional<SolveResult> told = fall_back(target, held, near)) {
    if (told->converged) model_.set_poses(told->poses);
    return std::move(*told);
  }
  poses_ = model_.poses();
  poses_[static_cast<size_t>(body_.value)] = target;
  if (!persist_) persist_ = std::make_unique<Session>(model_, options_, held_only(model_, body_));
  SolveResult r = persist_->solve(poses_);
  if (r.converged) model_.set_poses(poses_);
  add_spent(r, {held, near});
  return r;
}

// What the origin's pull `near` (from the model's poses) and then the turn tell of a step whose
// held solve failed (`spent`: its iterations, counted in the answer), each within its cap where
// the held solve that persists crawls to its stall rule (hundreds of iterations, no pose):
// - the pull ends out of reach: the nearest pose (OutOfReach);
// - the pull runs out of its steps still getting nearer (IterationLimit): the pose it reached,
//   valid and no farther from the target than the start, not called the nearest (a step in
//   reach but too long for them, as the vice's jaw moved 50: its screw would turn 250 times);
// - the pull gets there and the turn (Dragger::turn) ends out of reach or runs out of its steps:
//   its pose, as it says; the turn fails: that failure, with no pose;
// - the turn gets there: Converged, the held body at its target and every joint holding (the
//   model is not moved here).
// nullopt when the pull could not keep the joints: it tells nothing.
std::optional<SolveResult> Dragger::fall_back(const Pose& target, const SolveResult& spent,
                                              const SolveResult& near) {
  if (near.status == SolveStatus::OutOfReach) {
    SolveResult r = near;
    add_spent(r, {spent});
    return nearest(target, std::move(r));
  }
  if (near.status == SolveStatus::IterationLimit && near.violated().empty()) {
    return still_nearer(target, spent, near);
  }
  if (near.status != SolveStatus::Converged) return std::nullopt;
  // The origin got there: the rotation is pulled toward the target's with the origin held.
  SolveResult turned = turn(target, near.poses, spent.iterations + near.iterations);
  add_spent(turned, {spent, near});
  // (A turn that ran out of steps, still getting nearer, is told as it is.)
  if (turned.status == SolveStatus::OutOfReach || turned.angle_left > 0) {
    SolveResult r = nearest(target, std::move(turned));
    // What holding the body at its target leaves open there, largest first (a lock names its
    // couplings).
    const std::vector<ConstraintReport> open = violated_worst_first(r.constraints);
    for (size_t k = 0; k < open.size() && k < 3; ++k) {
      r.message += (k ? "; " : "; held there it leaves open: ") + describe(model_, open[k]);
    }
    return r;
  }
  if (!turned.converged) {
    // The turn could not keep the joints: no pose, what holding the body at its target leaves
    // open measured where the step began.
    const std::string why = turned.message;
    turned.status =
        turned.status == SolveStatus::Diverged ? SolveStatus::Diverged : SolveStatus::Stalled;
    turned.poses = model_.poses();
    turned.distance_left = turned.angle_left = 0;
    turned = nearest(target, std::move(turned));
    turned.message = "turn: '" + model_.body(body_).name +
                     "' could not be turned toward its target's rotation with its joints holding "
                     "(no pose is claimed): " +
                     why;
  }
  return turned;
}

// A pull that ran out of its steps while still getting nearer, as a drag step's result
// (IterationLimit): the pose it reached (its joints hold there), unless that is farther from the
// target than where the step began (the pull keeps only steps that get nearer; its last
// correction could move it by the tolerance), then the start. Not called the nearest.
SolveResult Dragger::still_nearer(const Pose& target, const SolveResult& spent,
                                  const SolveResult& near) const {
  SolveResult r = near;
  add_spent(r, {spent});
  r.status = SolveStatus::IterationLimit;
  r.converged = false;
  r.held = body_;
  const size_t held = static_cast<size_t>(body_.value);
  const double began = (model_.body(body_).pose.x - target.x).norm();
  r.distance_left = (r.poses[held].x - target.x).norm();
  if (r.distance_left > began) {
    r.poses = model_.poses();
    r.distance_left = began;
  }
  r = nearest(target, std::move(r));
  std::ostringstream msg;
  msg << "pull: '" << model_.body(body_).name << "' is still " << r.distance_left
      << " from its target after " << r.iterations
      << " iterations, getting nearer when they ran out (no nearest pose is claimed: the target "
         "may be in reach, farther than these iterations go)";
  r.message = msg.str();
  return r;
}

// The held body's rotation pulled toward the target's with its origin held where the target
// puts it, from `from` (a pose with the origin there and every joint holding). The pull makes
// least the angle between the body's rotation and the target's (a same rotation part), so every
// step it keeps is nearer. OutOfReach at the nearest pose when the rotation cannot get there
// (angle_left the angle between the body's rotation there and the target's); Converged with the
// held body at its target; IterationLimit with angle_left set when the pull ran out of steps
// while still getting nearer: the pose reached, no farther than `from`, and not called the
// nearest; else what the pull reached (the poses are the model's bodies', the constraints its
// joints). `spent`: the iterations the step took before the turn (kStepIterations).
SolveResult Dragger::turn(const Pose& target, const std::vector<Pose>& from, int spent) {
  if (!turn_ || turn_->revision != model_.revision()) {
    turn_ = std::make_unique<Turn>(model_, body_, options_);
  }
  std::vector<Pose> poses = from;
  poses.push_back(target);  // the ghost's
  const int all = std::max(0, kStepIterations - spent);
  const int left = std::max(0, all - kTurnReserve);
  SolveResult r = turn_->session->pull(poses, turn_->rotation, left, all);
  r.poses.pop_back();
  r.constraints.resize(static_cast<size_t>(model_.joint_count()));
  r.max_residual = largest_residual(r.constraints);
  r.held = body_;
  const size_t held = static_cast<size_t>(body_.value);
  r.distance_left = (r.poses[held].x - target.x).norm();
  // Got there: the poses as the pull left them and measured them, the held body within the
  // tolerance of its target (set at the target, its joints would be measured elsewhere: one
  // turn that got within 8.8e-10 rad of its target then left a joint 1.2e-9 open, over the
  // tolerance, and the step said it converged).
  if (r.status == SolveStatus::Converged) return r;
  if (r.status != SolveStatus::OutOfReach && r.status != SolveStatus::IterationLimit) return r;
  r.angle_left = r.poses[held].q.angularDistance(target.q);
  // Never farther than where it began (the pull keeps only steps that get nearer; its last
  // correction back onto the joints could move it by their tolerance): else the start itself.
  const double began = from[held].q.angularDistance(target.q);
  const std::string& name = model_.body(body_).name;
  std::ostringstream msg;
  if (r.angle_left > began) {
    r.status = SolveStatus::IterationLimit;
    r.poses = from;
    r.angle_left = began;
    msg << "turn: '" << name << "' found no pose nearer its target's rotation than where it "
        << "began, " << began << " rad from it (no nearest pose is claimed)";
  } else if (r.status == SolveStatus::OutOfReach) {
    msg << "out of reach: '" << name << "' stays " << r.angle_left
        << " rad from its target's rotation at the nearest pose its joints allow (its origin at "
           "the target's)";
  } else {
    msg << "turn: '" << name << "' is still " << r.angle_left
        << " rad from its target's rotation after " << r.iterations
        << " iterations, getting nearer when they ran out (its origin at the target's; no "
           "nearest pose is claimed)";
  }
  r.message = msg.str();
  return r;
}

// The pull of a step that cannot be made (its Newton steps failed, or its target is out of
// reach by the joints' lengths): the body's origin drawn toward the target's, at most
// kPullIterations Newton steps.
Puller& Dragger::puller() {
  if (!puller_) {
    SolveOptions capped = options_;
    capped.max_iterations = std::min(options_.max_iterations, kPullIterations);
    puller_ = std::make_unique<Puller>(model_, body_, Vec3::Zero(), capped);
  }
  return *puller_;
}

// A pull out of reach as a drag step's result: its poses the nearest, its constraints what
// holding the body at its target leaves open there.
SolveResult Dragger::nearest(const Pose& target, SolveResult near) const {
  std::vector<Pose> at_target = near.poses;
  at_target[static_cast<size_t>(body_.value)] = target;
  near.constraints = measure(model_, at_target, options_);
  near.max_residual = largest_residual(near.constraints);
  return near;
}

// A target the joints' lengths cannot reach: not solved for, but pulled toward for the nearest
// pose (at once when the stretched linkage breaks no joint: the Puller). Where the pull does not
// end out of reach (a path stretched breaks a joint, and the pull does not settle within its
// iterations), the bound alone: what is measured with the body at its target and the rest where
// it is (the joints on the stretched path are open), and the least distance left.
SolveResult Dragger::out_of_reach(const Pose& target) {
  SolveResult near = puller().pull_to(target.x, false);
  if (near.status == SolveStatus::OutOfReach) return nearest(target, std::move(near));
  const ReachBound::Gap gap = reach_->gap(target, options_.tolerance);
  SolveResult r;
  add_spent(r, {near});
  r.status = SolveStatus::OutOfReach;
  r.converged = false;
  r.poses = model_.poses();
  r.poses[static_cast<size_t>(body_.value)] = target;
  r.constraints = measure(model_, r.poses, options_);
  r.max_residual = largest_residual(r.constraints);
  r.held = body_;
  r.distance_left = gap.distance;
  std::ostringstream msg;
  msg << "out of reach: '" << model_.body(body_).name << "' stays at least " << gap.distance
      << " from its target (";
  describe_path(msg, model_, gap);
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
    msg << "dragged '" << model.body(body).name << "' in " << counted(steps, "step") << ", "
        << counted(out.iterations, "iteration");
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
