// The pull (pull.hpp): a constrained least-squares problem, min |soft residual|^2 with the hard
// joints held, solved from a valid pose by steps that each do two things:
// - a pull step: a Newton step in which the soft joint's rows are damped by `mu` (the polisher's
//   soft rows): it meets the hard rows to first order and goes toward the target as far as the
//   damping lets it; where the linkage cannot go (stretched, at a limit, at a loop's dead point)
//   its first-order model sees a way that is not there, and the damping bounds the step;
// - corrections: Newton steps on the hard joints alone (the soft rows damped out), back onto the
//   valid poses, quadratically.
// A step is kept when it ends nearer on valid poses (mu then shrinks, so a regular pull is
// Gauss-Newton and converges fast), else undone (mu grows). The pull stops when the target is
// reached, or when no step gets nearer by more than a thousandth of the tolerance: a point where
// the gradient of the distance is normal to the valid poses, the nearest pose (locally).
#include "dispcon/solve/pull.hpp"

#include <algorithm>
#include <cmath>

#include "dispcon/solve/group.hpp"

namespace dispcon {

namespace {

// Damping that takes the soft rows out of a step (the hard joints' corrections).
constexpr double kOut = 1e12;
// The first damping of the soft rows (relative to the largest diagonal entry), and its bounds:
// above kMaxDamping a step is a vanishing gradient step that still does not get nearer.
constexpr double kFirstDamping = 1e-4;
constexpr double kMinDamping = 1e-10;
constexpr double kMaxDamping = 1e4;
// Newton steps allowed to bring the hard joints back (from a valid pose: two or three suffice).
constexpr int kCorrections = 6;
// The weight of the hard joints' violation against the distance when steps are compared.
constexpr double kWeight = 10;

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

// Widens the band of each bounded joint the step pushed past its bound (the solver's rule for
// Newton steps, solver.cpp): true when one was.
bool widen(const SolverState& s, const Group& group, int joint, const std::vector<double>& joint_r,
           double tolerance, std::vector<double>& band) {
  bool widened = false;
  for (int c : group.joints) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    const double rc = joint_r[static_cast<size_t>(c)];
    double& b = band[static_cast<size_t>(c)];
    if (c != joint && js.bounded && rc > tolerance && b < 2 * rc &&
        s.at_limit(js, -0.5 * tolerance)) {
      b = std::max(4 * b, 2 * rc + tolerance);
      widened = true;
    }
  }
  return widened;
}

}  // namespace

PullOutcome pull_group(SolverState& s, const Group& group, int joint, Polisher& polisher,
                       PolishWork& work, std::vector<double>& band, const SolveOptions& o,
                       std::vector<double>& soft, PoseBuffer& before,
                       std::vector<double>& joint_r) {
  PullOutcome out;
  double& damping = soft[static_cast<size_t>(joint)];
  // Newton on the hard joints until they hold; false when they do not within kCorrections.
  Measure now = measure(s, group, joint, joint_r);
  // (Past the cap too: the poses a pull leaves must be valid whenever they can be.)
  auto correct = [&] {
    damping = kOut;
    double lambda = 1e-12;
    // To well within the tolerance, so that the distances compared are of valid poses alike.
    for (int k = 0; k < kCorrections && now.hard > 1e-3 * o.tolerance; ++k) {
      ++out.iterations;
      if (!polisher.step(s, work, band, lambda, o.max_rotation_step, false, false, &soft))
        return false;
      const Measure next = measure(s, group, joint, joint_r);
      if (!std::isfinite(next.hard)) return false;
      if (next.hard >= now.hard) lambda *= 100;
      now = next;
    }
    return now.hard <= o.tolerance;
  };
  save_poses(s, group, before);
  if (!correct()) {
    load_poses(s, group, before);
    now = measure(s, group, joint, joint_r);
    damping = 0;
    out.distance = now.distance;
    out.hard = now.hard;
    return out;
  }
  double mu = kFirstDamping;
  // Steps are compared by the distance plus the hard joints' violation times kWeight: one
  // correction follows each pull step, and the next pull step corrects what it leaves.
  auto merit = [](const Measure& m) { return m.distance + kWeight * m.hard; };
  while (now.distance > o.tolerance && out.iterations < o.max_iterations) {
    const Measure kept = now;
    save_poses(s, group, before);
    damping = mu;
    ++out.iterations;
    const bool stepped =
        polisher.step(s, work, band, 1e-12, o.max_rotation_step, false, false, &soft);
    if (stepped) now = measure(s, group, joint, joint_r);
    if (stepped && widen(s, group, joint, joint_r, o.tolerance, band)) {
      // A bound the step went past is met as a row from now on (the linkage slides along it
      // rather than the corrections undoing most of each step): the step is made again.
      load_poses(s, group, before);
      now = kept;
      continue;
    }
    bool corrected = stepped && std::isfinite(now.distance);
    if (corrected && now.hard > 1e-3 * o.tolerance && out.iterations < o.max_iterations) {
      damping = kOut;
      ++out.iterations;
      corrected = polisher.step(s, work, band, 1e-12, o.max_rotation_step, false, false, &soft);
      if (corrected) now = measure(s, group, joint, joint_r);
      corrected = corrected && std::isfinite(now.hard);
    }
    if (corrected && merit(now) < merit(kept)) {
      mu = std::max(kMinDamping, mu / 10);
      // Stationary: a kept step that gains less than the tolerance.
      if (merit(kept) - merit(now) < o.tolerance) {
        out.stationary = true;
        break;
      }
      continue;
    }
    load_poses(s, group, before);
    now = kept;
    mu *= 100;
    if (mu > kMaxDamping) {
      out.stationary = true;
      break;
    }
  }
  // Back onto the valid poses to well within the tolerance.
  if (!correct()) {
    load_poses(s, group, before);
  }
  damping = 0;
  now = measure(s, group, joint, joint_r);
  out.holds = now.hard <= o.tolerance;
  out.distance = now.distance;
  out.hard = now.hard;
  return out;
}

}  // namespace dispcon
