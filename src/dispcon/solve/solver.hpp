// The constraint processing loop (seed 2.2 step 2, 3.2) and what a solve reports.
//
// One iteration: every active joint proposes small rotations of its two bodies (eq. 18 and the
// angle and twist parts), the proposals are weighted by 1/max(n_i, n_j) and summed per body and
// applied; then every joint proposes translations from the rotated positions (eq. 19), weighted
// and summed likewise, and applied. Repeat until every joint holds within the tolerance.
// Variants are options of that one loop: Jacobi (the seed) or Gauss-Seidel ordering, a relaxation
// factor, and a final Newton polish whose steps are constraint impulses M^-1 J^T lambda, so they
// keep the seed's momentum conservation, continuity and closed loops.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dispcon/model/model.hpp"

namespace dispcon {

enum class Scheme { Jacobi, GaussSeidel };

struct SolveOptions {
  double tolerance = 1e-9;     // largest violation accepted (length units and radians)
  int max_iterations = 10000;  // seed iterations + polish iterations
  double time = 0;             // joints with time t0 t1 are active only when t0 <= time <= t1

  Scheme scheme = Scheme::Jacobi;
  bool seed_weights = true;            // weight by 1/max(n_i, n_j) (seed 3.2); false: plain sum
  double relaxation = 1.0;             // multiplies the weights
  double max_rotation_step = 0.2;      // radians a body may turn in one iteration (seed 2.3)
  bool translate_after_rotate = true;  // eq. 19 (exact in one iteration) vs eq. 15
  bool use_physics = true;  // bodies with mass and inertia use m J^-1 (eqs. 11-19); else k

  bool record_history = false;  // keep the largest violation after every iteration
  int threads = 0;  // independent groups of bodies shared among this many threads; 0: every
                    // core when there are several groups and 2,500 joints or more

  bool newton_polish = true;  // finish with Newton steps once close
  double polish_below = 0.1;  // switch to Newton when the largest violation is below this times
                              // the size of the group of bodies it moves (radians: below this)
};

// Throws std::invalid_argument (a ValueError naming the option) for a non-finite or out of
// range option: the options' door, called by every solve, session and analysis.
void validate(const SolveOptions& options);

// One joint as the solve left it.
struct ConstraintReport {
  JointId joint;
  int line = 0;
  double residual = 0;    // largest violation of its parts (length units or radians)
  bool satisfied = true;  // residual <= tolerance
  bool active = true;     // inactive joints (time interval) are reported satisfied
  bool at_limit = false;  // a bound (segment end, ring edge, angle or twist limit) is in contact
};

enum class SolveStatus {
  Converged,       // every active joint within tolerance
  IterationLimit,  // the cap was hit: over-constrained, unreachable, or too slow; see constraints
  Stalled,         // no progress for many iterations: over-constrained or unreachable
  Diverged,        // a non-finite residual or pose appeared; the poses were not changed
  OutOfReach,      // a drag step whose target the linkage cannot reach (see distance_left)
};

const char* to_string(SolveStatus status);

struct SolveResult {
  SolveStatus status = SolveStatus::Converged;
  bool converged = true;
  int iterations = 0;         // total
  int seed_iterations = 0;    // displacement-constraint iterations
  int polish_iterations = 0;  // Newton iterations
  double max_residual = 0;
  std::vector<ConstraintReport> constraints;  // one per joint, in model order
  std::vector<Pose> poses;                    // the poses reached (best effort when not converged)
  std::string message;                        // one line for people: what happened and where
  std::vector<double> history;  // largest violation after each iteration (record_history)
  // OutOfReach (a drag step): the held body, and how far its point stays from where the target
  // puts it at the least (length units): the joints cannot stretch that far.
  BodyId held{-1};
  double distance_left = 0;
  // OutOfReach with the held body's origin where the target puts it (distance_left within the
  // tolerance) but its rotation not: the angle (radians) between its rotation at the nearest
  // pose and the target's. 0 otherwise.
  double angle_left = 0;

  std::vector<JointId> violated() const;
};

// Solves from `poses` (one per body) in place; bodies with held[id] true do not move (as fixed).
// Never touches the model. `held` may be empty. `poses` change only when the solve converged,
// and then only the bodies of groups that had to move: the rest keep their bits.
SolveResult solve(const Model& model, std::vector<Pose>& poses, const SolveOptions& options,
                  const std::vector<bool>& held = {});

// A model solved again and again with the same structure (dragging, animation, a workbench's
// live drag): the working state, the groups of bodies and the Newton polish's symbolic
// factorisation are built once. The model must outlive the session; when it changed since (its
// revision: a body or joint added, a body fixed, ...), the session rebuilds before it solves.
class Session {
 public:
  // What a solve does when its damped Newton steps keep failing: Persist (seed iterations a
  // while, then Newton again, until the stall rule or the cap) or Stop at once, status Stalled
  // (a drag step's held solve, which then pulls instead: Dragger::move_to), or StopWhenSlow: as
  // Stop, and also after two whole Newton steps in a row that each leave more than half the
  // violation (slowed()), or after two steps in a row cut short so far from their end that the
  // seed's turn a step would take more than 60 steps in all to make it (far()).
  enum class Stuck { Persist, Stop, StopWhenSlow };
  Session(const Model& model, const SolveOptions& options, const std::vector<bool>& held = {},
          Stuck stuck = Stuck::Persist);
  ~Session();
  Session(Session&&) noexcept;
  Session& operator=(Session&&) noexcept;
  // Like solve(): from `poses`, updated in place when converged.
  SolveResult solve(std::vector<Pose>& poses);
  // A pull: every active joint but `joint` is held exactly, and `joint` is met as nearly as they
  // allow (least squares, a point joint: the distance), starting from `poses`, which should be
  // valid (they are corrected first). Status Converged when `joint` holds too, OutOfReach when the
  // others hold and `joint` stays open by distance_left (a local minimum of its residual, reached
  // by continuity from `poses`: no step gets nearer), IterationLimit when the others hold and the
  // cap came first, Stalled when the others could not be made to hold. `poses` are updated in
  // place in the first two cases; the result's poses are those reached. Throws
  // std::invalid_argument for an unknown or inactive joint. `most_iterations`, when not
  // negative, caps this pull's iterations below the options' cap. `all_iterations`, when not
  // negative, bounds every iteration, the last correction back onto the joints (made past the
  // cap) included: where it cannot make them hold by then, the pull ends IterationLimit at the
  // last pose it kept at which they held.
  SolveResult pull(std::vector<Pose>& poses, JointId joint, int most_iterations = -1,
                   int all_iterations = -1);
  // Whether the last solve stopped at slow whole steps (Stuck::StopWhenSlow).
  bool slowed() const;
  // Whether the last solve stopped at steps cut short too far from their end (likewise).
  bool far() const;
  // What the next solves do when stuck.
  void set_stuck(Stuck stuck);

 private:
  struct Impl;
  Impl& current();  // the state, rebuilt first when the model changed
  std::unique_ptr<Impl> impl_;
};

// Residual of every joint at the given poses, without moving anything.
std::vector<ConstraintReport> measure(const Model& model, const std::vector<Pose>& poses,
                                      const SolveOptions& options);

// Automatic assembly (seed 2.3): solves from the model's poses and stores the result in the
// model when it converged. A failed solve leaves the model as it was; the result holds the poses
// it reached.
SolveResult assemble(Model& model, const SolveOptions& options = {});

class ReachBound;

// A pull by a point (a workbench's mouse drag by a grabbed point, and a drag step that cannot be
// made): the point `point` (local) of `body` is drawn toward a world point as near as the joints
// let it, the body free to turn, every joint held exactly. From the model's poses, so the linkage
// stays on its branch; within a few dozen Newton steps at any size. Throws std::invalid_argument
// for the world, an unknown or a fixed body.
class Puller {
 public:
  Puller(Model& model, BodyId body, const Vec3& point, const SolveOptions& options = {});
  Puller(Puller&&) noexcept;
  ~Puller();
  // Draws the point toward `target` (checked: finite, within range). Status Converged when it
  // gets there, OutOfReach when the joints hold at the nearest pose they allow and the point stays
  // distance_left from the target (`held` is the body; a target farther from the fixed parts than
  // a path of point-to-point joints stretches, where the path stretched toward it breaks no
  // joint, gets that pose at once: the nearest there is), IterationLimit when the joints hold and
  // the point was still getting nearer at the cap (max_iterations; distance_left as reached),
  // Stalled or Diverged when the joints could not be made to hold. The result's poses are the
  // ones reached; with `move` true the model takes them whenever the joints hold there (it is
  // left as it was, bit for bit, otherwise). Its constraints are the model's joints.
  SolveResult pull_to(const Vec3& target, bool move = true);

 private:
  Model& model_;
  BodyId body_;
  Vec3 point_;
  SolveOptions options_;
  std::unique_ptr<ReachBound> reach_;  // built at the first pull, again when the model changed
  Model pulled_;  // the model and one more joint: the target (world) to the point
  JointId joint_{-1};
  std::uint64_t revision_ = 0;  // the model's when pulled_ was made
  std::unique_ptr<Session> session_;
};

// Interactive dragging (a mouse drag in the workbench): `body` is held at each target in turn
// while the rest follows from the previous result; the session is built once.
class Dragger {
 public:
  // Throws std::invalid_argument for the world, an unknown or a fixed body.
  Dragger(Model& model, BodyId body, const SolveOptions& options = {});
  Dragger(Dragger&&) noexcept;
  ~Dragger();
  // Holds the body at `target` (checked: a finite pose within range) and solves from the model's
  // poses. On success the model takes the new poses; otherwise it is left as it was, bit for bit,
  // and the result names what is violated. In order, while the step is not made:
  // - A target farther from the fixed parts than the joints can stretch is not solved for: it
  //   is pulled at once (OutOfReach with the nearest pose, without iterating when the linkage
  //   stretched toward the target breaks no joint); when that pull does not end out of reach
  //   either, the result has the bound alone as distance_left and the model's poses with the
  //   body at its target.
  // - The held solve: Newton steps, stopped at the first that fails, or after two whole steps in
  //   a row that each leave more than half the violation (a least-squares misfit settling, as
  //   where the target is out of reach; not near a path's full stretch, below), or after two
  //   steps in a row cut short so far from their end that the seed's 0.2 rad a step would take
  //   more than 60 steps in all (a target far out of reach, or in reach only by turning a long
  //   way: the vice's jaw moved 50, its screw turned 250 times).
  // - A linkage that can move as a whole (free in space, or on a plane along it): every body the
  //   held one reaches through joints between movable bodies carried with it rigidly, the step
  //   made at once when every joint holds there.
  // - After two slow whole steps, the pull (below) comes first, and only where it does not tell
  //   (it gets there, and the turn too) is the held solve made again without that rule, so a
  //   step in reach keeps its pose (the turn's pose when that solve fails). After far steps the
  //   pull and the turn alone.
  // - Near a path's full stretch (where those steps crawl) the path straightened by the one
  //   factor that meets the target (every body's direction across the line from the anchor
  //   scaled alike, the linkage kept on its branch), what hangs off it carried along, then the
  //   held solve from there.
  // - The pull (Puller): the body's origin drawn toward the target's, each Newton step followed
  //   by a search along the curve it traces and its damping set by a secant on the curvature
  //   found (the tension that a Gauss-Newton step leaves out: past a limit short of straight,
  //   out of an angle joint's plane, at a loop's dead point); a step cut short by the seed's
  //   turn is corrected only as far as its gain needs, the nearest pose to the tolerance. When
  //   it cannot get there the status is OutOfReach: the result's poses are the nearest valid
  //   pose, distance_left how far the body's origin stays from the target's there, and its
  //   constraints what holding the body at its target leaves open. When its 40 steps run out
  //   while it still gets nearer: IterationLimit with the pose it reached (valid, no farther
  //   than the start) and distance_left there, not called the nearest.
  // - When the origin got there, the body's rotation is pulled toward the target's with the
  //   origin held (a turn past a limit), the angle between the rotations made least:
  //   OutOfReach at the nearest pose, angle_left the angle left, no more than at the start;
  //   IterationLimit with angle_left set when its steps ran out still getting nearer (what is
  //   left of the step's 60 iterations after the held solve and the origin's pull: no nearest
  //   claimed); Converged with the turn's pose when it got there; Stalled, no pose, when
  //   it could not keep the joints. Only when the pull could not keep the joints does the held
  //   solve that persists (seed iterations, the stall rule) go on from where the step began.
  SolveResult move_to(const Pose& target);

 private:
  struct Turn;
  Puller& puller();
  SolveResult out_of_reach(const Pose& target);
  SolveResult pull(const Pose& target, SolveResult held, std::optional<SolveResult> pulled);
  std::optional<SolveResult> fall_back(const Pose& target, const SolveResult& spent,
                                       const SolveResult& near);
  SolveResult still_nearer(const Pose& target, const SolveResult& spent,
                           const SolveResult& near) const;
  SolveResult turn(const Pose& target, const std::vector<Pose>& from, int spent);
  SolveResult nearest(const Pose& target, SolveResult near) const;

  Model& model_;
  BodyId body_;
  SolveOptions options_;
  Session session_;
  std::unique_ptr<ReachBound> reach_;  // built at the first move, again when the model changed
  std::unique_ptr<Puller> puller_;     // built at the first step that fails
  std::unique_ptr<Session> persist_;   // the held solve that persists: after a pull that fails
  std::unique_ptr<Turn> turn_;         // built at the first step whose rotation is pulled
  std::vector<Pose> poses_;
};

struct DragResult {
  bool converged = true;
  int iterations = 0;              // total over steps
  double max_residual = 0;         // over steps
  std::vector<SolveResult> steps;  // one per step done
  int failed_step = -1;            // first step that did not converge, -1 when none
  std::string message;
};

// Dragging: assembles if needed, then moves `body` in `steps` equal steps (position linearly,
// rotation along the shortest arc) from its current pose to `target`, holding it at each step's
// pose while the rest follows. Each step starts from the last (continuity: no jump to another
// branch). Stops at the first step that fails and leaves the model at the last good step; when no
// step succeeded (the first fails, or the model does not assemble), the model is left bit for bit
// as it was before the call.
// When `step_poses` is given it receives every step's poses.
DragResult drag(Model& model, BodyId body, const Pose& target, int steps,
                const SolveOptions& options = {},
                std::vector<std::vector<Pose>>* step_poses = nullptr);

}  // namespace dispcon
