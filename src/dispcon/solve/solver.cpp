// The solve: each group iterates (seed iterations, then the Newton polish once close) until it
// holds, stalls or hits the cap; the result is measured and reported. Groups in group.cpp, the
// seed's iteration in seed_iteration.cpp, the polish in polish*.cpp, reports in report.cpp,
// dragging in drag.cpp, the options' checks in options.cpp.
#include "dispcon/solve/solver.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <deque>
#include <exception>
#include <limits>
#include <memory>
#include <stdexcept>
#include <thread>

#include "dispcon/solve/group.hpp"
#include "dispcon/solve/polish.hpp"
#include "dispcon/solve/pull.hpp"
#include "dispcon/solve/report.hpp"
#include "dispcon/solve/seed_iteration.hpp"

namespace dispcon {

namespace {

// The poses handed to a solve: one per body, each finite and within range (the door for poses
// that do not come from the model). Cheap when they are: nothing is allocated.
void check_poses(const Model& model, const std::vector<Pose>& poses) {
  if (static_cast<int>(poses.size()) != model.body_count()) {
    throw std::invalid_argument("solve: one pose per body expected");
  }
  for (size_t i = 0; i < poses.size(); ++i) {
    const Pose& p = poses[i];
    if (!p.x.allFinite() || !(p.x.cwiseAbs().maxCoeff() <= kLargest) || !p.q.coeffs().allFinite() ||
        !(p.q.coeffs().cwiseAbs().maxCoeff() > 0)) {
      check_pose(p, "position",
                 "solve: object '" + model.body(BodyId{static_cast<int>(i)}).name + "'");
    }
  }
}

// Iterations without a 0.1 % gain in the best violation after which a group is given up.
constexpr int kStallIterations = 400;
// With Session::Stuck::Stop, the damping of a failed Newton step beyond which the solve stops.
constexpr double kStopDamping = 1e-11;
// With Session::Stuck::StopWhenSlow, the solve stops after kSlowSteps whole Newton steps in a row
// (not cut short by the turn a body may make) that each leave more than kSlowStep of the
// violation: Newton's steps on joints that can be met close in quadratically, and whole steps
// that do not halve the violation are a least-squares misfit settling (a target out of reach).
constexpr double kSlowStep = 0.5;
constexpr int kSlowSteps = 2;
// With Session::Stuck::StopWhenSlow, the solve also stops after kSlowSteps Newton steps in a row
// each cut short to 1/N of itself (the turn a body may make, max_rotation_step a step) with the
// steps taken and N past kFarSteps: the first-order model asks for more turns of 0.2 rad than a
// few dozen steps make, so the held solve would crawl for at least that long (the vice's jaw
// moved 50 in one step: its screw asked to turn 7,854 times 0.2 rad, 5,451 Newton steps to a
// stall; the otary's ball held 50 away, out of reach: 2,837), and the pull (Dragger::move_to)
// tells sooner. One such step alone is not enough: the first steps of a far turn in reach can
// ask for many more than they end up needing (the monocycle's thigh turned 2.5 rad: 67 asked at
// its second step, made in 25).
constexpr int kFarSteps = 60;

// One group's run through the loop.
struct GroupRun {
  GroupRun(const Group& c, const SolverState& s) : group(&c), polisher(c) {
    for (int j : c.joints) {
      if (s.joints[static_cast<size_t>(j)].joint->coupling) couplings.push_back(j);
    }
  }
  const Group* group;
  Polisher polisher;
  // The group's couplings, whose turns each step it keeps follows (a held solve turns a screw
  // on past half a turn: SolverState::follow_couplings), and their phases and turns last seen at
  // the best poses (3 numbers a coupling), loaded with them.
  std::vector<int> couplings;
  std::vector<double> best_turns;
  int unfollowed = 0;  // steps kept since the couplings' turns were last followed
  double r = 0;        // largest violation now
  double best_r = 0;   // and the best seen, whose poses are kept
  double size = 1;     // the group's size when the session was made: where the polish begins
  double lambda = 1e-12;
  bool chord = false;  // the next Newton step may reuse the last factorisation (kept across solves)
  bool measured = false;  // the polisher measured the current poses (Polisher::measure)
  int iterations = 0, seed = 0, polish = 0;
  int seed_only_until = 0;   // after a failed polish, let the seed iterations work a while
  int last_progress = 0;     // the iteration at which the best violation last shrank by 0.1 %
  double progress_mark = 0;  // the best violation then
  bool stalled = false;
  bool slowed = false;  // stalled by slow whole steps (Session::Stuck::StopWhenSlow)
  bool far = false;     // stalled by a step cut short too far from its end (likewise)
  int slow = 0;         // whole steps in a row that did not halve the violation
  int far_steps = 0;    // steps in a row cut short too far from their end
  double asked = kInf;  // the fewest steps a step cut short asked for since the last whole one
  bool done = false;
  std::vector<double> history;  // r after each iteration (record_history)
  // The best poses seen of the group's bodies (in its order), kept from its run for finish() only
  // where it ended not converged (a buffer of the whole model's poses was 77 kB of the 400
  // four-bars' solve, on the command's heap at its peak; the run keeps them in its thread's work).
  PoseBuffer best;

  // Ready for another solve; the polisher keeps its symbolic analysis.
  void reset() {
    lambda = 1e-12;
    iterations = seed = polish = seed_only_until = last_progress = 0;
    stalled = slowed = far = false;
    slow = far_steps = 0;
    asked = kInf;
    unfollowed = 0;
    measured = false;
    done = false;
    history.clear();
  }
};

// The group's poses kept as its best (with its couplings' phases and turns last seen there), and
// loaded back.
void keep_turns(const SolverState& s, GroupRun& p) {
  p.best_turns.clear();
  for (int c : p.couplings) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    p.best_turns.insert(p.best_turns.end(), {js.phase, js.last[0], js.last[1]});
  }
}
template <typename Poses>
void keep_best(const SolverState& s, GroupRun& p, Poses& best) {
  save_group_poses(s, *p.group, best);
  keep_turns(s, p);
}
template <typename Poses>
void back_to_best(SolverState& s, const GroupRun& p, const Poses& best) {
  load_group_poses(s, *p.group, best);
  for (size_t k = 0; k < p.couplings.size() && 3 * k + 2 < p.best_turns.size(); ++k) {
    JointState& js = s.joints[static_cast<size_t>(p.couplings[k])];
    js.phase = p.best_turns[3 * k];
    js.last[0] = p.best_turns[3 * k + 1];
    js.last[1] = p.best_turns[3 * k + 2];
  }
}

// The turn (radians) two bodies may make against each other between the couplings' turns
// followed: well short of pi - kNearHalfTurn (coupling.cpp), where the short way round may flip.
constexpr double kFollowTurn = 1.0;

// After a step kept: the couplings' turns move on with it (SolverState::follow_couplings), so
// that a solve turns a screw or a gear as far as its steps go; unwrapped next to the turns the
// solve began from, a screw stopped near half a turn from them (pi + 0.5 rad), where the short
// way round flips. Each step turns a body by at most max_rotation_step, two bodies against each
// other by twice that: followed before the steps since could turn them past kFollowTurn (every
// other step at the seed's 0.2 rad), so that a solve of one step (a gear train's drag
// step) measures no coupling more. The residuals measured are unchanged by it.
void follow(SolverState& s, GroupRun& p, const SolveOptions& o) {
  if (p.couplings.empty()) return;
  if ((++p.unfollowed + 1) * 2 * o.max_rotation_step <= kFollowTurn) return;
  s.follow_couplings(p.couplings);
  p.unfollowed = 0;
}

// One iteration of one group: a Newton polish step once close, else a seed iteration.
// Limits enter the Newton step only when violated. A step that pushes a limit that was not in
// the step over its bound is redone with that limit held at its bound: its band (what counts as
// contact) is widened to cover the distance the step moved it, so the active set grows instead
// of the step being damped.
void iterate(SolverState& s, GroupRun& p, PolishWork& work, const SolveOptions& o,
             std::vector<double>& band, std::vector<double>& joint_r, Session::Stuck stuck) {
  const Group& group = *p.group;
  const double polish_threshold = o.polish_below * p.size;
  ++p.iterations;
  // A session that stops when stuck (a drag step, which pulls then) takes Newton steps from the
  // start: its poses are valid but for the held body, and the pull is its fallback.
  const bool polish =
      o.newton_polish && (stuck != Session::Stuck::Persist ||
                          (p.r < polish_threshold && p.iterations > p.seed_only_until));
  if (!polish) {
    if (o.scheme == Scheme::Jacobi) {
      jacobi_iteration(s, group, o);
    } else {
      gauss_seidel_iteration(s, group, o);
    }
    ++p.seed;
    follow(s, p, o);
    p.r = max_residual(s, group.joints, joint_r);
    p.measured = false;
    return;
  }
  ++p.polish;
  save_group_poses(s, group, work.before_);
  p.polisher.allow_small_chord(stuck == Session::Stuck::Persist);
  const bool stepped =
      p.polisher.step(s, work, band, p.lambda, o.max_rotation_step, p.chord, p.measured);
  p.measured = false;
  const bool chord = p.polisher.reused();
  // The residuals, with what a chord step from here needs, in one pass over the joints.
  const double next = stepped ? p.polisher.measure(s, band, joint_r) : p.r;
  if (stepped && next < p.r) {
    p.measured = true;
    follow(s, p, o);
    // After a Newton step the next may reuse its factorisation (a small group's only after a
    // step that gained a hundredfold); a chord step that gained less than a hundredfold asks for
    // a new one.
    const bool gained = next < 0.01 * p.r;
    p.chord = (chord || p.polisher.small_chord_ready()) ? gained : true;
    if (stuck == Session::Stuck::StopWhenSlow) {
      const bool slow = !chord && next > kSlowStep * p.r && !p.polisher.cut_short();
      p.slow = slow ? p.slow + 1 : 0;
      p.slowed = p.stalled = p.slow >= kSlowSteps;
      // Steps asked for: this one's 1/N of itself. Where each ask is half a step or more below
      // every one before it, the steps close in on the target as the first order says (the
      // vice's jaw moved 0.5: 79 steps), and only the stall rule's count is too many.
      const double asked = p.polisher.cut_short() ? 1 / p.polisher.step_scale() : 0;
      const bool closing = asked <= p.asked - 0.5 && p.iterations + asked <= kStallIterations;
      const bool far = p.polisher.cut_short() && p.iterations + asked > kFarSteps && !closing;
      p.asked = p.polisher.cut_short() ? std::min(p.asked, asked) : kInf;
      p.far_steps = far ? p.far_steps + 1 : 0;
      p.far = p.far_steps >= kSlowSteps;
      p.stalled = p.stalled || p.far;
    }
    p.r = next;
    p.lambda = std::max(1e-12, p.lambda * 0.1);
    return;
  }
  if (chord) {  // the old factorisation no longer serves: try again with a new one
    load_group_poses(s, group, work.before_);
    p.chord = false;
    return;
  }
  bool widened = false;
  if (stepped) {
    for (int c : group.joints) {
      const JointState& js = s.joints[static_cast<size_t>(c)];
      double& b = band[static_cast<size_t>(c)];
      const double rc = s.residual(js);
      if (rc > p.r && b < polish_threshold && s.at_limit(js, -0.5 * o.tolerance)) {
        b = std::max(4 * b, 2 * rc + o.tolerance);
        widened = true;
      }
    }
  }
  load_group_poses(s, group, work.before_);
  if (!widened) p.lambda *= 100;
  if (stuck != Session::Stuck::Persist && (!stepped || p.lambda > kStopDamping)) {
    // The caller pulls instead (a drag step: Dragger::move_to): damped Newton steps that keep
    // failing are a linkage that cannot be where it is held, or a step too long for the
    // first-order model; either way seed iterations would crawl.
    p.stalled = true;
    return;
  }
  if (!stepped || p.lambda > 1e-2) {
    p.lambda = 1e-12;
    p.seed_only_until = p.iterations + 10;
  }
}

bool all_finite(const std::vector<Pose>& poses) {
  for (const Pose& p : poses) {
    if (!p.x.allFinite() || !p.q.coeffs().allFinite()) return false;
  }
  return true;
}

}  // namespace

struct Session::Impl {
  Impl(const Model& m, const SolveOptions& opt, const std::vector<bool>& held_bodies,
       Stuck when_stuck)
      : model((validate(opt), m)),
        revision(m.revision()),
        held(held_bodies),
        stuck(when_stuck),
        o(opt),
        s(m, m.poses(), opt, held_bodies),
        groups(find_groups(s)) {
    for (const Group& g : groups) runs.emplace_back(g, s);
    band.assign(s.joints.size(), -0.5 * opt.tolerance);
    for (GroupRun& p : runs) p.size = group_size(s, *p.group);
    threads = thread_count(opt, groups);
    more_work.resize(static_cast<size_t>(std::max(0, threads - 1)));
    for (size_t c = 0; c < s.joints.size(); ++c) {
      const JointState& js = s.joints[c];
      if (js.active && !s.bodies[static_cast<size_t>(js.b1)].movable &&
          !s.bodies[static_cast<size_t>(js.b2)].movable) {
        immovable.push_back(static_cast<int>(c));
      }
    }
  }

  // A solve, in order: start from the poses, run every group to its end, then measure and report.
  void start(const std::vector<Pose>& poses);
  void run_groups();
  void run(GroupRun& p, PolishWork& work);
  void run_iterations(GroupRun& p, PolishWork& work);
  PullOutcome run_pull(int joint, int most);
  SolveResult finish(const std::vector<Pose>& poses);

  const Model& model;
  std::uint64_t revision;  // the model's when this was built
  std::vector<bool> held;
  Stuck stuck;
  SolveOptions o;
  SolverState s;
  std::vector<Group> groups;
  std::deque<GroupRun> runs;  // not moved once built: each holds its factorisation
  std::vector<double> band;
  // A pull's poses before its step and its spare (the Newton and seed steps keep theirs in the
  // work's own, of a group's bodies only), set at each pull from the poses given; and the last
  // valid poses a pull with its iterations bounded kept (a turn's: pull_group).
  PoseBuffer spare, before, valid;
  PullWork pull_work;                        // the rest of a pull's scratch
  const std::vector<Pose>* given = nullptr;  // the poses the solve started from
  std::vector<double> joint_r;               // each joint's residual at the current poses
  PolishWork work;
  std::deque<PolishWork> more_work;  // one per extra thread
  int threads = 1;                   // threads a solve uses
  std::vector<int> immovable;        // active joints whose two bodies cannot move
  std::vector<double> soft;          // a pull's damping per joint (pull.hpp)
  int reached = -1;                  // the joint whose last pull reached its target, or -1
  std::atomic<bool> finite{true};    // no residual has become infinite or not a number
};

Session::Session(const Model& model, const SolveOptions& options, const std::vector<bool>& held,
                 Stuck stuck)
    : impl_(std::make_unique<Impl>(model, options, held, stuck)) {}
Session::~Session() = default;
Session::Session(Session&&) noexcept = default;
Session& Session::operator=(Session&&) noexcept = default;

SolveResult solve(const Model& model, std::vector<Pose>& poses, const SolveOptions& o,
                  const std::vector<bool>& held) {
  return Session(model, o, held).solve(poses);
}

std::vector<ConstraintReport> measure(const Model& model, const std::vector<Pose>& poses,
                                      const SolveOptions& options) {
  validate(options);
  check_poses(model, poses);
  const SolverState s(model, poses, options, {});
  return report(s, options.tolerance);
}

Session::Impl& Session::current() {
  if (impl_->model.revision() != impl_->revision) {
    // The model changed since this session was built: its joints may have moved in memory.
    std::vector<bool> held = impl_->held;
    if (!held.empty()) held.resize(static_cast<size_t>(impl_->model.body_count()), false);
    impl_ = std::make_unique<Impl>(impl_->model, impl_->o, held, impl_->stuck);
  }
  return *impl_;
}

SolveResult Session::solve(std::vector<Pose>& poses) {
  Impl& session = current();
  check_poses(session.model, poses);
  session.start(poses);
  if (session.finite) session.run_groups();
  SolveResult result = session.finish(poses);
  if (result.converged) poses = result.poses;
  result.message = solve_message(session.model, result);
  return result;
}

bool Session::slowed() const {
  for (const GroupRun& p : impl_->runs) {
    if (p.slowed) return true;
  }
  return false;
}

bool Session::far() const {
  for (const GroupRun& p : impl_->runs) {
    if (p.far) return true;
  }
  return false;
}

void Session::set_stuck(Stuck stuck) {
  impl_->stuck = stuck;
}

SolveResult Session::pull(std::vector<Pose>& poses, JointId joint, int most_iterations,
                          int all_iterations) {
  Impl& session = current();
  // The cap for this pull alone (the options' again after it, however it ends).
  struct Cap {
    int& at;
    int was;
    ~Cap() { at = was; }
  } cap{session.o.max_iterations, session.o.max_iterations};
  if (most_iterations >= 0) cap.at = std::min(cap.was, most_iterations);
  check_poses(session.model, poses);
  if (joint.value < 0 || joint.value >= session.model.joint_count()) {
    throw std::invalid_argument("pull: no joint " + std::to_string(joint.value));
  }
  session.start(poses);
  PullOutcome pulled;
  if (session.finite) {
    pulled = session.run_pull(
        joint.value, all_iterations >= 0 ? all_iterations : std::numeric_limits<int>::max());
  }
  SolveResult result = session.finish(poses);
  // finish() judged the hard joints; the pulled joint is reported as measured.
  result.max_residual = std::max(result.max_residual, pulled.distance);
  result.distance_left = pulled.distance;
  if (result.converged && pulled.distance > session.o.tolerance) {
    // Nearer than this no step gets (stationary), or the cap came first.
    result.status = pulled.stationary ? SolveStatus::OutOfReach : SolveStatus::IterationLimit;
    result.converged = false;
  }
  if (result.status == SolveStatus::Converged || result.status == SolveStatus::OutOfReach) {
    poses = result.poses;
  }
  result.message = solve_message(session.model, result);
  return result;
}

// The group of the pulled joint is pulled; the others solve as usual (serially: a pull is an
// interactive drag's frame, its other groups untouched by it).
PullOutcome Session::Impl::run_pull(int joint, int most) {
  soft.assign(s.joints.size(), 0.0);
  PullOutcome out;
  bool found = false;
  for (GroupRun& p : runs) {
    const std::vector<int>& joints = p.group->joints;
    if (std::find(joints.begin(), joints.end(), joint) == joints.end()) {
      if (finite) run(p, work);
      continue;
    }
    found = true;
    before.assign(given->begin(), given->end());
    spare.assign(given->begin(), given->end());
    out = pull_group(s, *p.group, joint, p.polisher, work, band, o, soft, before, spare, valid,
                     pull_work, joint_r, reached == joint, most);
    reached = out.holds && out.distance <= o.tolerance ? joint : -1;
    p.measured = false;  // the pull moved the poses since the first measure
    p.iterations = p.polish = out.iterations;
    p.r = p.best_r = out.hard;
    keep_best(s, p, p.best);
    p.done = true;
    p.stalled = !out.holds;
    if (!std::isfinite(out.hard) || !std::isfinite(out.distance)) finite = false;
  }
  if (!found) {
    throw std::invalid_argument("pull: joint " + std::to_string(joint) +
                                " is not active or moves nothing");
  }
  return out;
}

void Session::Impl::start(const std::vector<Pose>& poses) {
  s.read_poses(poses);
  joint_r.assign(s.joints.size(), 0.0);
  finite = true;
  std::fill(band.begin(), band.end(), -0.5 * o.tolerance);
  for (GroupRun& p : runs) {
    p.reset();
    // With what a first chord step needs, when the group has a factorisation from a last solve;
    // the joints of bodies that have not moved since are not measured again.
    p.r = p.best_r = p.progress_mark = p.polisher.measure(s, band, joint_r, true);
    p.measured = true;
    keep_turns(s, p);
    p.done = p.r <= o.tolerance;
    if (!std::isfinite(p.r)) finite = false;
  }
  given = &poses;
}

// Each group runs to the end before the next starts, so its working set stays in cache; with
// many groups, several threads take the next unsolved group in turn (each group touches only
// its own bodies and joints, so the answer does not depend on the threads).
void Session::Impl::run_groups() {
  if (threads <= 1) {
    for (GroupRun& p : runs) {
      if (!finite) break;
      run(p, work);
    }
    return;
  }
  std::atomic<size_t> next{0};
  std::vector<std::exception_ptr> errors(static_cast<size_t>(threads));
  auto worker = [&](int t) {
    try {
      PolishWork& mine = t == 0 ? work : more_work[static_cast<size_t>(t - 1)];
      for (size_t i; finite && (i = next++) < runs.size();) run(runs[i], mine);
    } catch (...) {
      errors[static_cast<size_t>(t)] = std::current_exception();
      finite = false;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker, t);
  worker(0);
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

void Session::Impl::run(GroupRun& p, PolishWork& scratch) {
  // The best poses so far: those given, until an iteration does better.
  const std::vector<int>& bodies = p.group->bodies;
  scratch.best_.resize(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) {
    scratch.best_[i] = (*given)[static_cast<size_t>(bodies[i])];
  }
  run_iterations(p, scratch);
  // finish() takes a group's best poses back where it did not converge.
  if (!p.done || p.stalled) p.best.assign(scratch.best_.begin(), scratch.best_.end());
}

void Session::Impl::run_iterations(GroupRun& p, PolishWork& scratch) {
  for (int k = 0; !p.done && k < o.max_iterations; ++k) {
    iterate(s, p, scratch, o, band, joint_r, stuck);
    if (!std::isfinite(p.r)) {
      finite = false;
      return;
    }
    if (p.r < p.best_r) {
      p.best_r = p.r;
      keep_best(s, p, scratch.best_);
    }
    // An over-constrained or unreachable problem stops improving: give up early rather than
    // run to the cap (a drag step that cannot be made should fail fast).
    if (p.best_r < (1 - 1e-3) * p.progress_mark) {
      p.progress_mark = p.best_r;
      p.last_progress = p.iterations;
    } else if (p.iterations - p.last_progress > kStallIterations) {
      p.stalled = true;
    }
    p.done = p.r <= o.tolerance || p.stalled;
    if (o.record_history) p.history.push_back(p.r);
  }
}

SolveResult Session::Impl::finish(const std::vector<Pose>& poses) {
  SolveResult result;
  for (const GroupRun& p : runs) result.iterations = std::max(result.iterations, p.iterations);
  if (o.record_history) {
    // The largest violation over groups after each iteration, as if they had advanced in
    // lockstep (a group that finished early keeps its last violation).
    result.history.assign(static_cast<size_t>(result.iterations), 0.0);
    for (const GroupRun& p : runs) {
      for (size_t k = 0; k < result.history.size(); ++k) {
        result.history[k] = std::max(result.history[k], k < p.history.size() ? p.history[k] : p.r);
      }
    }
  }
  // The poses reached: a group that did not have to move keeps the bits it was given.
  result.poses = poses;
  double r = 0;
  bool any_stalled = false;
  for (GroupRun& p : runs) {
    if ((!p.done || p.stalled) && finite) {
      back_to_best(s, p, p.best);  // not converged: keep the best poses seen
      p.r = p.best_r;
      max_residual(s, p.group->joints, joint_r);
    }
    if (p.iterations > 0) save_poses(s, *p.group, result.poses);
    // A group that ends where it last measured keeps that measure for the next solve's first.
    if (p.done && !p.stalled && p.measured && finite) p.polisher.keep_measure(s, joint_r);
    any_stalled = any_stalled || p.stalled;
    r = std::max(r, p.r);
    if (p.iterations == result.iterations) {
      result.seed_iterations = std::max(result.seed_iterations, p.seed);
      result.polish_iterations = std::max(result.polish_iterations, p.polish);
    }
  }
  // Joints between bodies that cannot move are measured too: nothing can fix them.
  r = std::max(r, max_residual(s, immovable, joint_r));
  if (!std::isfinite(r) || !all_finite(result.poses)) finite = false;
  if (!finite) {
    // Named by their residuals where it happened; the poses go back to those given, bit for bit.
    result.status = SolveStatus::Diverged;
    result.converged = false;
    result.max_residual = std::numeric_limits<double>::infinity();
    result.constraints = report(s, o.tolerance, &joint_r);
    result.poses = poses;
    s.read_poses(poses);
    return result;
  }
  if (r > o.tolerance) {
    result.status = any_stalled ? SolveStatus::Stalled : SolveStatus::IterationLimit;
    result.converged = false;
  }
  result.max_residual = r;
  result.constraints = report(s, o.tolerance, &joint_r);
  return result;
}

SolveResult assemble(Model& model, const SolveOptions& options) {
  std::vector<Pose> poses = model.poses();
  SolveResult r = solve(model, poses, options);
  if (r.converged) model.set_poses(poses);
  return r;
}

}  // namespace dispcon
