// The pull (pull.hpp): a constrained least-squares problem, min |soft residual|^2 with the hard
// joints held, solved from a valid pose by steps that each do three things:
// - a pull step: a Newton step in which the soft joint's rows are damped by `mu` (the polisher's
//   soft rows): it meets the hard rows to first order and goes toward the target as far as the
//   damping lets it;
// - corrections: Newton steps on the hard joints alone (the soft rows damped out), back onto the
//   valid poses, quadratically;
// - a search along the curve those two trace (the step scaled by t, then corrected): where the
//   target cannot be met (stretched, at a limit, at a loop's dead point) the soft residual's
//   curvature along the valid poses is not the Gauss-Newton model's |J dq|^2: it has a second
//   term, the residual times the curvature of the valid poses (the tension), which that model
//   leaves out. Near a loop's dead point it is all there is (the soft point's first-order motion
//   vanishes), and past a limit short of straight or out of an angle joint's plane it makes the
//   Gauss-Newton step too long by the ratio of the target's distance to the reach. The values of
//   half the squared residual at the step's start (with its slope r . J dq, exact) and at the
//   corrected end measure that curvature along the step, a parabola puts the nearest point of
//   the curve (tried too when it lies far from the end), and the damping of the next step is
//   set so that its model has the curvature found (a secant on the tension): the next step is
//   then about Newton's, and the pull converges superlinearly instead of linearly. Where the
//   tension is negative (the valid poses bend toward the target: inside a crank's circle) no
//   damping gives that curvature; the damping is kept and the next step is stretched to the
//   parabola's least point instead.
// A step is kept when it ends nearer on valid poses, else undone (mu grows). The pull stops when
// the target is reached, when a kept step gains less than the tolerance, or when the next step
// promises to gain less than a thousandth of it: a point where the gradient of the distance is
// normal to the valid poses, the nearest pose (locally).
#include "dispcon/solve/pull.hpp"

#include <algorithm>
#include <cmath>

#include "dispcon/solve/group.hpp"
#include "dispcon/solve/rim.hpp"

namespace dispcon {

namespace {

// Damping that takes the soft rows out of a step (the hard joints' corrections).
constexpr double kOut = 1e12;
// The first damping of the soft rows (relative to the largest diagonal entry), and its bounds:
// above kMaxDamping a step is a vanishing gradient step that still does not get nearer.
constexpr double kFirstDamping = 1e-4;
// The first damping of a pull that follows one which reached its target (the next frame of a drag
// in reach): its target is most likely in reach too, and a step damped by kFirstDamping stops
// 5% short of it on a large group (the 100-part drag's frames in reach: 5 Newton steps, 4 with
// this; 1e-8 takes as many). Only after a target reached: as every pull's first damping, 1e-8
// made the steps out of reach dearer (the planar arm out of its plane 20 -> 29 steps).
constexpr double kFollowDamping = 1e-6;
// The least damping of a point's pull: there the hard rows yield to the soft ones by at most a
// ten-thousandth of the distance (kRegularised / kMinDamping). At 1e-10 (a hundredth) the
// four-bar held past its dead point took two pull steps more (24 -> 26), its steps near the
// dead point as long as the seed allows and overshooting.
constexpr double kMinDamping = 1e-8;
// The regularisation of the hard rows in a pull step.
constexpr double kRegularised = 1e-12;
// The least damping of a turn's soft rows (a joint of rotation parts alone: Dragger::turn's).
// The hard rows, regularised by kRegularised, yield to the soft ones by about that over the
// damping times the soft residual, which for a turn is the angle it cannot make (radians, of order
// 1): at 1e-10 a hundredth of it, 0.02 rad on the robot arm's hand turned 2.5 rad against its
// wrist's cone, where 0.004 rad was left to gain along the bound; the curve search measured the
// yield that the corrections undo as gain, and the secant, taking the yield for the damping's
// share, lowered the damping further (the turn alone: 70 steps; 50 with the corrections' floor
// below, 21 with this too). A point's pull (every Puller's) keeps kMinDamping.
constexpr double kMinTurnDamping = 1e-6;
constexpr double kMaxDamping = 1e4;
// Newton steps allowed to bring the hard joints back (from a valid pose: two or three suffice).
constexpr int kCorrections = 6;
// Points of a step's curve tried (its end first), and how far from the last tried the parabola's
// nearest point must lie for another (a fraction of that point's t).
constexpr int kCurvePoints = 3;
constexpr double kCloseEnough = 0.25;
// A tension below -kBends of the Gauss-Newton curvature is met by stretching the step (at most
// kMaxStretch times its model's length) rather than by lowering the damping.
constexpr double kBends = 1e-3;
constexpr double kMaxStretch = 2;
// The share of the first-order gain of a turn's step cut short by the seed's turn that what its
// corrections leave may move h by (a hundredth elsewhere). A far turn's steps are mostly cut
// short (a light body asked to turn far more than the held one, the monocycle's foot 6-14 rad,
// limits them to 2-15 % of the step), and corrections were about 60 % of a far turn's
// iterations, two or three a point: mostly one now, the next step correcting the rest. Measured
// on the sweep (far_targets_test.cpp): at 0.1 no step loses a nearest pose; at 0.15-0.2 the
// steering's pinion about z lost its nearest (the violation each step left grew from step to
// step, 0.002 to 0.027, and h measured at the kept pose, off the valid poses, was lower than at
// any valid point next to it); at 0.3 the robot arm's upper arm about z stalled.
constexpr double kTurnCutShare = 0.1;

using Vec6 = PolishWork::Vec6;

struct Measure {
  double hard = 0, distance = 0;
};

Measure measure(const SolverState& s, const Group& group, int joint, std::vector<double>& joint_r) {
  Measure m;
  max_residual(s, group.joints, joint_r);
  for (int c : group.joints) {
    const double r = joint_r[static_cast<size_t>(c)];
    if (c == joint) {
      m.distance = r;
    } else if (!(r <= m.hard)) {
      m.hard = std::isnan(r) ? HUGE_VAL : r;
    }
  }
  return m;
}

// The bounds a pull holds as rows, and those it has let go. A bound a step went past is held
// from then on (widen(): its joint's band widened, so the linkage slides along it rather than the
// corrections undoing most of each step). A held bound is let go when the step's impulse on its
// rows pushes it out past the bound (release()): the rest of the step would take it back inside,
// so leaving it gets nearer (the multiplier of an active-set step with the wrong sign: for one
// bound, the step without its rows stays inside it to first order). Held for good, the robot
// arm's hand turned 2 rad about (0, 1, 1) stopped with its wrist's twist at its limit, 4.8e-4 rad
// farther than the nearest pose, which leaves it; a pull along a guide stopped at the guide's end.
// Only after a whole step (one cut short by the seed's turn is far from the nearest pose, where
// the bounds' curvature outweighs their first order), and once a kept step.
class Holds {
 public:
  Holds(double tolerance, size_t joints) : joints_(joints) { let_go.band = -0.5 * tolerance; }

  // Before a step from the current poses: the rows each held bound will have in it (the step's
  // rows come joint by joint, part by part, as the polisher gathers them).
  void find(const SolverState& s, const Group& group, int joint, const std::vector<double>& band) {
    held_.clear();
    bool any = false;
    for (int c : group.joints) any = any || (c != joint && band[static_cast<size_t>(c)] > 0);
    if (!any) return;
    PartRows parts[kPartSlots];
    double out[kPartSlots][3];
    int row = 0;
    for (int c : group.joints) {
      const JointState& js = s.joints[static_cast<size_t>(c)];
      if (!js.bounded) {
        // A joint without bounds has as many rows at every pose: counted once.
        if (fixed_rows_.empty()) fixed_rows_.assign(joints_, -1);
        int& count = fixed_rows_[static_cast<size_t>(c)];
        if (count < 0) {
          s.rows(js, BoundTest{band[static_cast<size_t>(c)]}, parts, false);
          count = parts[0].count + parts[1].count + parts[2].count + parts[3].count;
        }
        row += count;
        continue;
      }
      const JointBounds bound = test(c, band);
      s.rows(js, bound, parts, false);
      // A bounded joint other than the pull's whose band a step widened: its bounds are held.
      const bool holds = c != joint && bound.bound.band > 0;
      if (holds) s.outward(js, bound, out);
      for (int p = 0; p < kPartSlots; ++p) {
        const PartRows& rows = parts[p];
        // (A bound let go that has rows is passed, by rounding or more: not held.)
        if (holds && rows.at_limit && (bound.let_go_parts >> p & 1u) == 0 &&
            (out[p][0] != 0 || out[p][1] != 0 || out[p][2] != 0)) {
          held_.push_back({c, p, row, rows.count, {out[p][0], out[p][1], out[p][2]}});
        }
        row += rows.count;
      }
    }
    rows_ = row;
  }

  // After the step: lets go of each held bound whose rows' impulses (y, the step's) push it out
  // past the bound, by more than rounding; true when one was. (Nothing when the step's rows are
  // not those counted: a twist whose axes turned opposite has none.)
  bool release(const std::vector<double>& y) {
    if (held_.empty() || y.size() != static_cast<size_t>(rows_)) return false;
    double largest = 0;
    for (double v : y) largest = std::max(largest, std::abs(v));
    bool released = false;
    for (const Held& h : held_) {
      double push = 0;
      for (int k = 0; k < h.count && k < 3; ++k)
        push += y[static_cast<size_t>(h.row + k)] * h.out[k];
      if (push > 1e-9 * largest && (wait_.empty() || wait_[static_cast<size_t>(h.joint)] == 0)) {
        if (let_go.parts.empty()) let_go.parts.resize(joints_, 0);
        let_go.parts[static_cast<size_t>(h.joint)] |= static_cast<unsigned char>(1u << h.part);
        released = true;
      }
    }
    return released;
  }

  // A step went past a bound it had let go (by more than the tolerance): held again.
  bool hold_again(const SolverState& s, const JointState& js, int c, double tolerance) {
    if (let_go.parts.empty() || let_go.parts[static_cast<size_t>(c)] == 0) return false;
    PartRows parts[kPartSlots];
    s.rows(js, BoundTest{-0.5 * tolerance}, parts, false);
    unsigned char& mine = let_go.parts[static_cast<size_t>(c)];
    const unsigned char before = mine;
    for (int p = 0; p < kPartSlots; ++p) {
      if (parts[p].at_limit) mine = static_cast<unsigned char>(mine & ~(1u << p));
    }
    if (mine == before) return false;
    // The step that passed it went further than its first order said (by the bound's curvature:
    // the monocycle's hip, a cone of 0.04 rad, was let go and passed again at every other step,
    // each a step made twice): the joint's bounds are not let go again for 2, 4, 8, ... kept
    // steps.
    if (wait_.empty()) wait_.resize(joints_, 0), times_.resize(joints_, 0);
    const auto k = static_cast<size_t>(c);
    wait_[k] = 2 << std::min(times_[k]++, 10);
    return true;
  }

  // A step was kept.
  void kept() {
    for (int& w : wait_) w = std::max(0, w - 1);
  }
  // The bound test of joint c's rows in a step.
  JointBounds test(int c, const std::vector<double>& band) const {
    JointBounds t{BoundTest{band[static_cast<size_t>(c)]}};
    if (!let_go.parts.empty()) {
      t.let_go_parts = let_go.parts[static_cast<size_t>(c)];
      t.let_go = let_go.band;
    }
    return t;
  }

  LetGo let_go;

 private:
  struct Held {
    int joint, part, row, count;
    double out[3];
  };
  std::vector<Held> held_;
  std::vector<int> fixed_rows_;  // the rows of each joint without bounds (-1: not yet counted)
  // Per joint: the kept steps before its bounds may be let go again, and how often they were
  // held again.
  std::vector<int> wait_, times_;
  int rows_ = 0;
  size_t joints_ = 0;
};

// Widens the band of each bounded joint the step pushed past its bound (the solver's rule for
// Newton steps, solver.cpp), and holds again a bound let go that it passed: true when one was.
bool widen(const SolverState& s, const Group& group, int joint, const std::vector<double>& joint_r,
           double tolerance, std::vector<double>& band, Holds& holds) {
  bool widened = false;
  for (int c : group.joints) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    const double rc = joint_r[static_cast<size_t>(c)];
    double& b = band[static_cast<size_t>(c)];
    if (c == joint || !js.bounded || !(rc > tolerance) || !s.at_limit(js, -0.5 * tolerance)) {
      continue;
    }
    const bool again = holds.hold_again(s, js, c, tolerance);
    if (b < 2 * rc || again) {
      b = std::max(4 * b, 2 * rc + tolerance);
      widened = true;
    }
  }
  return widened;
}

// The soft joint's rows at the current poses: half their squared residuals (what the pull makes
// least), and along a step dq the slope and curvature of the first-order model of it.
struct SoftRows {
  PartRows parts[kPartSlots];

  double read(const SolverState& s, const JointState& js, double band, bool jacobian) {
    s.rows(js, BoundTest{band}, parts, jacobian);
    double h = 0;
    for (const PartRows& p : parts) {
      for (int k = 0; k < p.count; ++k) h += p.residual[k] * p.residual[k];
    }
    return 0.5 * h;
  }
  // Of h(t) = |r + t J dq|^2 / 2 at t = 0: h'(0) = r . J dq, h''(0) = |J dq|^2 (the rows read
  // with their Jacobian; dq one 6-vector per unknown, as the polisher numbers them).
  void along(const SolverState& s, const JointState& js, const std::vector<Vec6>& dq, double& slope,
             double& curvature) const {
    auto motion = [&](int b) {
      const BodyState& body = s.bodies[static_cast<size_t>(b)];
      return body.movable ? dq[static_cast<size_t>(body.n_var)] : Vec6(Vec6::Zero());
    };
    const Vec6 d1 = motion(js.b1), d2 = motion(js.b2);
    slope = curvature = 0;
    for (const PartRows& p : parts) {
      for (int k = 0; k < p.count; ++k) {
        const double v = p.J[k].head<6>().dot(d1) + p.J[k].tail<6>().dot(d2);
        slope += p.residual[k] * v;
        curvature += v * v;
      }
    }
  }
};

// The group moved from `from` by t times the step dq, as Polisher::step moves it (each body
// turned about its centre, then its centre moved).
void move_along(SolverState& s, const Group& group, const PoseBuffer& from,
                const std::vector<Vec6>& dq, double t) {
  load_poses(s, group, from);
  for (size_t v = 0; v < group.bodies.size(); ++v) {
    s.bodies[static_cast<size_t>(group.bodies[v])].displace(t * dq[v].head<3>(),
                                                            t * dq[v].tail<3>());
  }
}

// A turn's reduced quasi-Newton steps (rim.hpp) from the kept pose the model last observed, one
// after another while they are kept: each moved by the model's step, corrected onto the valid
// poses as a pull step's end is, and kept when it gains what a sufficient decrease asks (a
// ten-thousandth of what the model predicts), else undone (and the pull's own steps go on).
// Stationary: once a step gained as the model predicted (within a factor of two), where the
// model's whole next step (not held to the trust radius) promises less than the pull's own
// steps must (a tenth of the tolerance, in distance).
struct RimRun {
  bool kept = false;        // a step was kept
  bool stationary = false;  // see above
};

template <typename Correct>
RimRun rim_steps(RimModel& rim, SolverState& s, const Group& group, int joint,
                 const std::vector<double>& band, const LetGo& let_go, double band_soft,
                 const SolveOptions& o, PoseBuffer& before, std::vector<double>& joint_r,
                 Measure& now, double& h, SoftRows& rows, int& iterations, std::vector<Vec6>& dq,
                 Correct&& correct) {
  RimRun out;
  const JointState& pulled = s.joints[static_cast<size_t>(joint)];
  double predicted = 0;
  while (iterations < o.max_iterations && now.distance > o.tolerance) {
    if (rim.validated() &&
        rim.whole_gain() < 0.1 * o.tolerance * std::max(now.distance, o.tolerance)) {
      out.stationary = true;
      return out;
    }
    if (!rim.propose(o.max_rotation_step, dq, predicted)) break;
    const Measure kept = now;
    const double h0 = h;
    save_poses(s, group, before);
    ++iterations;
    move_along(s, group, before, dq, 1);
    now = measure(s, group, joint, joint_r);
    // The hard joints corrected until what they leave moves h by a hundredth of the gain
    // predicted; within the tolerance unless the step was cut short to the seed's turn (as a
    // pull step's: far from the nearest pose, the next step corrects the rest).
    const double gain =
        std::max(1e-3 * o.tolerance, 1e-2 * predicted / std::max(kept.distance, o.tolerance));
    const double within = rim.cut_short() ? gain : std::min(o.tolerance, gain);
    bool valid = std::isfinite(now.distance) && correct(within) && std::isfinite(now.distance);
    if (valid && now.distance < 10 * o.tolerance) valid = correct(1e-3 * o.tolerance);
    const double ht = valid ? rows.read(s, pulled, band_soft, false) : HUGE_VAL;
    const bool keep = ht < h0 - 1e-4 * predicted;
    const double ratio = (h0 - ht) / predicted;
    rim.judge(ratio, keep);
    if (!keep) {
      load_poses(s, group, before);
      now = kept;
      rows.read(s, pulled, band_soft, true);
      return out;
    }
    h = rows.read(s, pulled, band_soft, true);
    out.kept = true;
    s.follow_couplings(group.joints);  // (as the pull's kept steps: SolverState::follow_couplings)
    if (!rim.observe(s, group, joint, band, band_soft, let_go)) return out;
  }
  return out;
}

// Whether the group has couplings, whose turns a pull follows after each kept step (a pull along
// a screw goes on past half a turn: SolverState::follow_couplings).
bool has_couplings(const SolverState& s, const Group& group) {
  for (int c : group.joints) {
    if (s.joints[static_cast<size_t>(c)].joint->coupling) return true;
  }
  return false;
}

// What a step's curve gave at its valid points: the rise of h over its start at the longest and
// the shortest tried. A step that goes down (slope < 0) from a pose on a smooth curve of valid
// poses rises less, then falls, as t shrinks; where h rises about as much at a tenth of the step
// as at the whole, the corrected poses are not near the pose they started from (a bound held
// again as a row from a pose inside it: the corrections put the part at the bound, a fixed rise;
// the snake's tail 0.025 inside its rod's end, 0.003 up at every t). No damping gets such a step
// nearer, so the pull stops there, but that pose is no nearest one.
struct Rises {
  double far_t = 0, far = 0, near_t = 0, near = 0;
  void add(double t, double rise) {
    if (far_t == 0 || t > far_t) far_t = t, far = rise;
    if (near_t == 0 || t < near_t) near_t = t, near = rise;
  }
  bool jump() const { return near > 0 && near_t <= 0.1 * far_t && near >= 0.5 * far; }
};

}  // namespace

PullOutcome pull_group(SolverState& s, const Group& group, int joint, Polisher& polisher,
                       PolishWork& work, std::vector<double>& band, const SolveOptions& o,
                       std::vector<double>& soft, PoseBuffer& before, PoseBuffer& spare,
                       PoseBuffer& valid, PullWork& pw, std::vector<double>& joint_r, bool follows,
                       int most) {
  PullOutcome out;
  const JointState& pulled = s.joints[static_cast<size_t>(joint)];
  double& damping = soft[static_cast<size_t>(joint)];
  // Newton on the hard joints until they hold; false when they do not within kCorrections.
  Measure now = measure(s, group, joint, joint_r);
  Holds holds(o.tolerance, s.joints.size());
  const bool couplings = has_couplings(s, group);
  // (Past the cap too: the poses a pull leaves must be valid whenever they can be.)
  // To well within the tolerance by default, so that the distances compared are of valid poses
  // alike; to `within` where what is compared is larger.
  auto correct = [&](double within) {
    damping = kOut;
    double lambda = kRegularised;
    for (int k = 0; k < kCorrections && now.hard > within && out.iterations < most; ++k) {
      ++out.iterations;
      if (!polisher.step(s, work, band, lambda, o.max_rotation_step, false, false, &soft,
                         &holds.let_go))
        return false;
      const Measure next = measure(s, group, joint, joint_r);
      if (!std::isfinite(next.hard)) return false;
      // Within the tolerance, a step that does not halve what the hard joints leave has met
      // their floor: they cannot all hold exactly (the robot arm's hand held at its origin, which
      // it reaches with its elbow 4e-12 past its limit, leaves 2.4e-12 at every joint), and the
      // kCorrections steps would change nothing.
      const bool floor = next.hard <= o.tolerance && !(next.hard < 0.5 * now.hard);
      if (next.hard >= now.hard) lambda *= 100;
      now = next;
      if (floor) break;
    }
    return now.hard <= std::max(within, o.tolerance);
  };
  save_poses(s, group, before);
  if (!correct(1e-3 * o.tolerance)) {
    load_poses(s, group, before);
    now = measure(s, group, joint, joint_r);
    damping = 0;
    out.distance = now.distance;
    out.hard = now.hard;
    return out;
  }
  SoftRows rows;
  const double band_soft = band[static_cast<size_t>(joint)];
  double h = rows.read(s, pulled, band_soft, true);
  std::vector<Vec6>& dq = pw.dq;
  // A pose on the way is corrected only as far as its step's gain asks; before the pull is judged
  // stationary at one, it is corrected to well within the tolerance (the distances compared
  // there are then of valid poses) and the pull goes on from it: true when it was; false when
  // the pose already was (or cannot be) corrected so: the pull is stationary there.
  auto tighten = [&] {
    if (now.hard <= o.tolerance || !correct(1e-3 * o.tolerance)) {
      out.stationary = true;
      return false;
    }
    h = rows.read(s, pulled, band_soft, true);
    return true;
  };
  const Joint& soft_joint = *pulled.joint;
  const double least = soft_joint.has_hinge || soft_joint.guide || soft_joint.coupling
                           ? kMinDamping
                           : kMinTurnDamping;
  double mu = follows ? kFollowDamping : kFirstDamping;
  // A turn's model of its objective on the free directions (rim.hpp).
  const bool turn = soft_joint.same_rotation;
  RimModel* rim = nullptr;
  if (turn) {
    if (!pw.rim) pw.rim = std::make_unique<RimModel>();
    rim = pw.rim.get();
    rim->reset();
  }
  // Where the valid poses bend toward the target (the tension negative: a target inside a
  // crank's circle), no damping gives the step the curvature found, which is less than the
  // Gauss-Newton model's: the step is stretched instead, to the least point of the parabola the
  // last step measured (1D Newton along the step: a one-degree-of-freedom group converges
  // superlinearly, where the damping's floor left the distance/reach share of the error a step).
  double stretch = 1;
  double gained = 0;        // the last kept step's gain (0: none yet)
  bool calibrated = false;  // mu was set by the secant: the step's model has the curvature found
  bool moved = false;       // a step was kept
  bool may_release = true;  // no bound let go since the last kept step
  bool jumped = false;      // the last step tried found the valid poses off its start (Rises)
  // One pull step from the current poses (kept in `before`), damped by mu, the held bounds found
  // again: an iteration.
  auto pull_step = [&] {
    save_poses(s, group, before);
    damping = mu;
    ++out.iterations;
    holds.find(s, group, joint, band);
    return polisher.step(s, work, band, kRegularised, o.max_rotation_step, false, false, &soft,
                         &holds.let_go);
  };
  // Whether a pull step from the current poses, undone, lets go of a held bound (its impulses
  // push it outward: Holds::release); when it does the pull goes on without it.
  auto release_probe = [&] {
    if (out.iterations >= o.max_iterations) return false;
    const Measure at = now;
    const bool stepped = pull_step();
    const bool released =
        stepped && !polisher.cut_short() && polisher.has_multipliers() && holds.release(work.y_);
    load_poses(s, group, before);
    now = at;
    rows.read(s, pulled, band_soft, true);
    if (released) may_release = false;
    return released;
  };
  // With `most` bounded: the last pose kept at which the hard joints hold (the start's at least),
  // where the pull ends if its last correction cannot make them hold within `most`.
  const bool bounded = most < std::numeric_limits<int>::max();
  bool kept_valid = false;
  while (now.distance > o.tolerance && out.iterations < o.max_iterations) {
    const Measure kept = now;
    if (bounded && now.hard <= o.tolerance) {
      save_group_poses(s, group, valid);
      kept_valid = true;
    }
    const double h0 = h;
    jumped = false;
    const bool stepped = pull_step();
    if (stepped) now = measure(s, group, joint, joint_r);
    // A bound the step went past is met as a row from now on (the linkage slides along it
    // rather than the corrections undoing most of each step): the step is made again. Not a
    // turn's step cut short by the seed's turn after a kept one (far from the nearest pose): it
    // goes on to its curve, whose corrections, the band widened, put the part at the bound, and
    // the next step holds it. A pull step spared each time (up to 7 of a far turn's steps were
    // made twice). (The first step is made again: its curve, kinked by the bound, set the next
    // damping 9,000 times its own on the robot arm's upper arm turned about z, which then ran
    // out of its iterations 1e-8 rad short of the nearest pose it had reached after 43; now 30.)
    // With kTurnCutShare, the robot arm's hand turned 3 rad about z and about (1, -2, 0.5) ends
    // at the nearest pose within the drag step's 60 iterations again (53 and 42).
    if (stepped && widen(s, group, joint, joint_r, o.tolerance, band, holds) &&
        !(turn && polisher.cut_short() && moved)) {
      load_poses(s, group, before);
      now = kept;
      rows.read(s, pulled, band_soft, true);
      continue;
    }
    if (stepped && may_release && !polisher.cut_short() && polisher.has_multipliers() &&
        holds.release(work.y_)) {
      // A bound held that this step's impulses push outward is let go, and the step made again
      // without it (once a kept step: a bound let go that the step then passes is held again).
      may_release = false;
      load_poses(s, group, before);
      now = kept;
      rows.read(s, pulled, band_soft, true);
      continue;
    }
    double slope = 0, gauss_newton = 0;
    if (stepped) {
      dq.assign(work.dq_.begin(), work.dq_.begin() + static_cast<long>(group.bodies.size()));
      rows.along(s, pulled, dq, slope, gauss_newton);
    }
    // The step's own model along it: h0 + slope t + (gauss_newton + damped) t^2 / 2, least at
    // t = 1, so its curvature is -slope; the damping's share of it is what the secant adjusts.
    const double damped = -slope - gauss_newton;
    // The step undone and more damping asked for: false when that is past its bound (a
    // vanishing gradient step that still does not get nearer: stationary).
    auto undo_and_damp = [&] {
      load_poses(s, group, before);
      now = kept;
      rows.read(s, pulled, band_soft, true);
      mu *= 100;
      calibrated = false;
      return mu <= kMaxDamping;
    };
    if (!stepped || !(slope < 0)) {
      // No step, or one that does not go down: the gradient vanishes on the valid poses (to
      // rounding) or the step is not to be had; more damping, else stationary.
      if (stepped || !undo_and_damp()) {
        load_poses(s, group, before);
        now = kept;
        if (tighten()) continue;
        break;
      }
      continue;
    }
    // What the step promises, converted to distance (h = d^2 / 2): its model's least value when
    // the damping was set by the secant, else Gauss-Newton's along it (which the tension only
    // makes smaller where the linkage bends away from the target). A step that promises less
    // than a tenth of the tolerance is not taken. The model's slope counts the hard rows'
    // yield (kRegularised against mu: they give way by that share of the soft residual, a slope
    // of about -2 h0 kRegularised / mu), which the corrections undo: left out of the promise.
    // Near the nearest pose outside a crank's circle it is most of the slope (2.2e-11 of
    // 2.25e-11), and a step promising nothing else was made and its curve searched (2 Newton
    // steps) before the pull stopped.
    const double yield = 2 * h0 * kRegularised / mu;
    const double promise = calibrated         ? -0.5 * (slope + yield)
                           : gauss_newton > 0 ? slope * slope / (2 * gauss_newton)
                                              : HUGE_VAL;
    if (promise < 0.1 * o.tolerance * std::max(kept.distance, o.tolerance)) {
      load_poses(s, group, before);
      now = kept;
      if (tighten()) continue;
      break;
    }
    // The step as made (Polisher::step scales it so no body turns more than the seed allows).
    const double longest = polisher.step_scale();
    // Along the curve: the step's end (stretched, see above) corrected first; then, while the
    // parabola through (0, h0, slope) and the last point tried promises much more than that point
    // gave, its least point (no farther than the step as made, or twice a whole step).
    const bool stretched = longest >= 1 && stretch > 1;
    double t = stretched ? stretch : longest, best_t = 0, best_h = h0, curvature = 0;
    Measure best = kept;
    int flat = 0;
    double tp = 0, hp = 0;  // the last valid point tried before t, and h there
    Rises rises;
    for (int k = 0; k < kCurvePoints && out.iterations < o.max_iterations; ++k) {
      if (t != longest) {  // (the step as made is where the polisher left the group)
        move_along(s, group, before, dq, t);
        now = measure(s, group, joint, joint_r);
      }
      // The hard joints corrected until what they leave moves h by a hundredth of the gain the
      // step's first order promises there (h moves by about d times the violation): within the
      // tolerance, and on a step cut short by the turn its bodies may make (a pull on its way,
      // not yet near the nearest pose: the next step corrects the rest with its own) no further
      // than that, which spares a correction or two a step. A turn's step cut short: a tenth
      // (kTurnCutShare).
      const double share = turn && longest < 1 ? kTurnCutShare : 1e-2;
      const double gain =
          std::max(1e-3 * o.tolerance, share * -slope * t / std::max(kept.distance, o.tolerance));
      const double within = longest < 1 ? gain : std::min(o.tolerance, gain);
      // A whole step's first point is first corrected as loosely as a cut-short step's; then,
      // where the valid poses bend toward the target (the next step is stretched and closes in
      // fast), only until what is left moves h by a hundredth of what the parabola says the next
      // step can gain (one correction after a crank's tenth of a radian instead of two), else
      // to `within`.
      const bool lax = longest >= 1 && k == 0;
      bool valid = correct(lax ? gain : within) && std::isfinite(now.distance);
      // Near the target what the corrections leave is of the order of the distance: to well
      // within the tolerance there, as at the end.
      if (valid && now.distance < 10 * o.tolerance) valid = correct(1e-3 * o.tolerance);
      double ht = valid ? rows.read(s, pulled, band_soft, false) : HUGE_VAL;
      if (lax && valid && now.hard > within) {
        const double c = 2 * (ht - h0 - slope * t) / (t * t);
        const bool bends = c > 0 && ht < h0 && c - gauss_newton < -kBends * gauss_newton;
        const double left = bends ? ht - (h0 - 0.5 * slope * slope / c) : 0;
        const double allowed = std::min(gain, 1e-2 * left / std::max(now.distance, o.tolerance));
        if (now.hard > allowed) {
          valid = correct(std::max(within, allowed)) && std::isfinite(now.distance);
          ht = valid ? rows.read(s, pulled, band_soft, false) : HUGE_VAL;
        }
      }
      if (valid) rises.add(t, ht - h0);
      if (ht < best_h) {
        best_t = t, best_h = ht, best = now;
        save_poses(s, group, spare);
      }
      double next = 0.25 * t;  // no valid pose there: a shorter step
      if (valid && std::abs(ht - h0) < 0.01 * -slope * t) {
        // h does not move along the valid poses where the step's first order says it should,
        // here and a tenth of the way: the step's motion of the soft rows is one the hard joints
        // do not allow (their rows yield by the regularisation, lambda against the pull's
        // damping), and nothing is to be gained.
        if (++flat == 2) break;
        next = 0.1 * t;
      } else if (valid) {
        curvature = 2 * (ht - h0 - slope * t) / (t * t);
        // Where an earlier point overshot (h above h0 there), the parabola through the three
        // values instead: near a loop's dead point h is far from the first order's parabola (a
        // crank's tenth of a radian past it, the slope's parabola put the least 3.5 times too far
        // and a third point was tried; the three values put it within the 25% kept).
        double s1 = slope;
        if (tp > 0 && hp > h0 && std::abs(tp - t) > 1e-3 * t) {
          const double d1 = (ht - h0) / t, d2 = (hp - h0) / tp;
          const double c3 = 2 * (d2 - d1) / (tp - t);
          if (c3 > 0 && d1 - 0.5 * c3 * t < 0) curvature = c3, s1 = d1 - 0.5 * c3 * t;
        }
        // A turn whose valid poses rise above the start both here and at a quarter or less of
        // the last point tried: not a curve that falls from its start (its slope is negative),
        // but corrections that jump off it (a bound held as a row from a pose inside it: the
        // corrections put the part at the bound whatever t). A shorter t rises as well and
        // takes as many corrections (the otary's tail turned about x: a third point of 6
        // corrections, rising, on each of its steps undone): the step is undone now.
        if (turn && ht > h0 && tp > 0 && hp > h0 && t <= 0.25 * tp) break;
        const double least = curvature > 0 ? -s1 / curvature : HUGE_VAL;
        // The parabola's least value, and what the point tried gave of it.
        const double lowest = curvature > 0 ? h0 + 0.5 * s1 * least : -HUGE_VAL;
        if (ht < h0 && ht - lowest <= kCloseEnough * (h0 - lowest)) break;
        if (ht < h0 && least > t && t >= longest) break;  // the rest in the next step
        next = std::min(least, longest < 1 ? longest : 2.0);
      }
      next = std::max(next, 1e-3 * t);
      if (std::abs(next - t) <= 1e-3 * t) break;
      if (valid) tp = t, hp = ht;
      t = next;
    }
    if (flat == 2) {
      load_poses(s, group, before);
      now = kept;
      if (!moved && mu > least) {
        // Or the pull began where h is stationary without being least (a loop's dead point
        // seen from a target it moves toward either way; a pull that got nearer ends at a
        // least point): the step undamped goes as far as the seed allows, and gets off it if
        // it can.
        rows.read(s, pulled, band_soft, true);
        mu = least;
        calibrated = false;
        continue;
      }
      if (tighten()) continue;
      break;
    }
    if (best_t == 0) {
      jumped = rises.jump();
      if (!undo_and_damp()) {
        if (tighten()) continue;
        break;
      }
      continue;
    }
    load_poses(s, group, spare);
    if (couplings) s.follow_couplings(group.joints);
    moved = true;
    may_release = true;
    holds.kept();
    now = best;
    h = rows.read(s, pulled, band_soft, true);
    // The next step's damping: the curvature found along this one less the Gauss-Newton share
    // (the tension the model leaves out), as a multiple of this step's damping.
    stretch = 1;
    if (curvature > 0 && damped > 0 && curvature - gauss_newton < -kBends * gauss_newton &&
        longest >= 1) {
      // The damping kept, the next step stretched as this one's curve asked (its model is least
      // at t = 1, the curve at -slope / curvature).
      stretch = std::min(-slope / curvature, kMaxStretch);
      calibrated = true;
    } else if (curvature > 0 && damped > 0) {
      const double wanted = std::max(curvature - gauss_newton, 1e-4 * damped);
      mu = std::clamp(mu * wanted / damped, least, kMaxDamping);
      calibrated = true;
    } else {
      mu = std::max(least, mu / 10);
      calibrated = false;
    }
    // A turn: the reduced quasi-Newton steps after a whole step (rim.hpp); stationary where
    // their model says so and the step's impulses let go of no held bound (one pull step, made
    // and undone, as a kept step's release() would judge it).
    bool holding = false;  // a bound held as a row (its band widened)
    for (int c : group.joints)
      holding = holding || (c != joint && band[static_cast<size_t>(c)] > 0);
    // (Observed after steps cut short too, for the pairs: only after whole steps, 14 of the 36
    // turns of the robot arm's hand took 1-7 iterations more.)
    if (turn && holding && rim->observe(s, group, joint, band, band_soft, holds.let_go) &&
        longest >= 1) {
      const RimRun run = rim_steps(*rim, s, group, joint, band, holds.let_go, band_soft, o, before,
                                   joint_r, now, h, rows, out.iterations, pw.rim_dq, correct);
      if (run.stationary) {
        if (release_probe()) continue;
        if (tighten()) continue;
        break;
      }
      if (run.kept) continue;
    }
    // Stationary: a kept step that gains less than the tolerance.
    const double gain = kept.distance - now.distance;
    if (gain < o.tolerance) {
      if (tighten()) continue;
      break;
    }
    // Or, after two stretched steps (Newton along each: where the group moves one way only, a
    // crank's circle, the gains fall faster than linearly, each at most its share of the last
    // times itself), one whose gain says the next would gain less than a tenth of the tolerance,
    // on a target out of reach (the distance left much larger than the gains; in reach it falls
    // as fast as they do). Not after damped steps: where the tension couples modes of different
    // stiffness (the planar arm held out of its plane) a fast mode's gains fall so while a slow
    // one's go on linearly.
    const bool superlinear = stretched && gained > 0 && gain < 0.1 * gained &&
                             gain * gain < 0.1 * o.tolerance * gained && now.distance > 100 * gain;
    gained = stretched ? gain : 0;
    if (superlinear) {
      out.stationary = true;
      break;
    }
  }
  // Ended where the last step's valid poses jumped off the pose kept: no step from it gets
  // nearer, but not because it is least (Rises): no nearest pose is claimed.
  if (jumped) out.stationary = false;
  // Back onto the valid poses to well within the tolerance; where `most` stopped that short of
  // the tolerance, back to the last valid pose kept.
  if (!correct(1e-3 * o.tolerance)) {
    if (kept_valid && out.iterations >= most) {
      load_group_poses(s, group, valid);
      out.stationary = false;
    } else {
      load_poses(s, group, before);
    }
  }
  damping = 0;
  now = measure(s, group, joint, joint_r);
  out.holds = now.hard <= o.tolerance;
  out.distance = now.distance;
  out.hard = now.hard;
  return out;
}

}  // namespace dispcon
