// Seed 2.2: 1. each solid moves as if free (eqs. 1-4); 2. the constraints are re-established by
// displacement corrections (the physics variant: m J^-1 and mu = m2/(m1+m2), so the corrections
// conserve the first-order momenta); 3. the speeds become those of the positions reached.
#include "dispcon/solve/dynamics.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "dispcon/solve/counted.hpp"

namespace dispcon {

namespace {

struct Speed {
  Vec3 v = Vec3::Zero();  // of the centre of mass, world
  Vec3 w = Vec3::Zero();  // angular, world
};

// Eqs. 1-4 over h for every free body with mass; returns the largest rotation of the step.
double free_motion(const Model& model, const AnimateOptions& o, double h, std::vector<Pose>& poses,
                   std::vector<Speed>& speed) {
  double largest = 0;
  for (int i = 1; i < model.body_count(); ++i) {
    const Body& b = model.body(BodyId{i});
    if (b.fixed || !b.mass) continue;
    Pose& p = poses[static_cast<size_t>(i)];
    Speed& s = speed[static_cast<size_t>(i)];
    const double m = *b.mass;
    s.v += (b.force / m + o.gravity) * h;  // (1)
    if (b.inertia) {
      const Mat3 R = p.rotation();
      const Mat3 J = R * *b.inertia * R.transpose();
      s.w += J.inverse() * (b.torque - s.w.cross(J * s.w)) * h;  // (2), with the gyroscopic term
    }
    const Vec3 G = p.apply(b.center) + s.v * h;  // (3), for the centre of mass
    // (4) with the exact exponential of the rotation vector h w, renormalised.
    p.q = (quat_from_rotation_vector(s.w * h) * p.q).normalized();
    p.x = G - p.q * b.center;
    largest = std::max(largest, (s.w * h).norm());
  }
  return largest;
}

// Within what the model accepts (numbers.hpp): beyond, the next solve would refuse it.
bool usable(const Vec3& v) {
  return v.allFinite() && v.cwiseAbs().maxCoeff() <= kLargest;
}

bool usable(const std::vector<Pose>& poses, const std::vector<Speed>& speed) {
  for (size_t i = 0; i < poses.size(); ++i) {
    if (!usable(poses[i].x) || !poses[i].q.coeffs().allFinite() || !usable(speed[i].v) ||
        !usable(speed[i].w))
      return false;
  }
  return true;
}

std::vector<bool> active_set(const Model& model, double t) {
  std::vector<bool> a;
  for (const Joint& j : model.joints()) a.push_back(j.active_at(t));
  return a;
}

}  // namespace

void validate(const AnimateOptions& o) {
  check_number(o.duration, "duration", "duration");
  if (o.duration < 0) throw ValueError("duration", "duration must not be negative");
  check_number(o.dt, "dt", "dt");
  if (!(o.dt > 0)) throw ValueError("dt", "dt " + format_number(o.dt) + " must be positive");
  const double frames = std::ceil(o.duration / o.dt - 1e-9);
  if (!(frames <= kMaxFrames)) {
    throw ValueError("duration", "duration " + format_number(o.duration) + " / dt " +
                                     format_number(o.dt) + " makes " + format_number(frames) +
                                     " frames (at most " + format_number(kMaxFrames) + ")");
  }
  check_vector(o.gravity, "gravity", "gravity");
  check_number(o.max_step_rotation, "max_step_rotation", "max_step_rotation");
  if (!(o.max_step_rotation > 0))
    throw ValueError("max_step_rotation", "max_step_rotation must be positive");
  validate(o.solve);
}

AnimateResult animate(Model& model, const AnimateOptions& o) {
  validate(o);
  AnimateResult out;
  SolveOptions so = o.solve;
  so.time = 0;
  so.use_physics = true;
  std::vector<Pose> poses = model.poses();
  // Start from valid positions (seed 2.3): speeds are not touched by the assembly.
  const SolveResult start = solve(model, poses, so);
  out.iterations += start.iterations;
  if (!start.converged) {
    out.converged = false;
    out.message = "the model does not assemble at t = 0: " + start.message;
    return out;
  }
  std::vector<Speed> speed(static_cast<size_t>(model.body_count()));
  for (int i = 1; i < model.body_count(); ++i) {
    const Body& b = model.body(BodyId{i});
    if (b.fixed) continue;
    speed[static_cast<size_t>(i)].v = b.velocity;
    speed[static_cast<size_t>(i)].w = b.spin;
  }
  out.frames.push_back({0.0, start.iterations, start.max_residual, true, false, {}, poses});

  const int frames = static_cast<int>(std::ceil(o.duration / o.dt - 1e-9));
  std::vector<bool> active = active_set(model, 0);
  Session session(model, so);
  for (int f = 1; f <= frames; ++f) {
    const double t0 = (f - 1) * o.dt;
    const double t1 = std::min(o.duration, f * o.dt);
    Frame frame;
    frame.time = t1;
    // Sub-steps: when a step would turn a body by more than the limit, go back and halve it.
    double t = t0;
    while (t < t1 - 1e-15) {
      double h = t1 - t;
      std::vector<Pose> trial;
      std::vector<Speed> trial_speed;
      for (int halvings = 0;; ++halvings) {
        trial = poses;
        trial_speed = speed;
        const double turn = free_motion(model, o, h, trial, trial_speed);
        if (turn <= o.max_step_rotation || halvings >= 30) break;
        h *= 0.5;
      }
      // Step 2 at the step's end time.
      so.time = t + h;
      const std::vector<bool> now = active_set(model, so.time);
      if (now != active) {
        session = Session(model, so);
        active = now;
      }
      const std::vector<Pose> before = poses;
      if (!usable(trial, trial_speed)) {
        frame.diverged = true;
        break;
      }
      SolveResult r = session.solve(trial);
      if (r.status == SolveStatus::Diverged) {
        frame.diverged = true;
        frame.violated = r.violated();
        break;
      }
      if (!r.converged) trial = r.poses;  // the seed goes on with what it reached
      frame.iterations += r.iterations;
      frame.max_residual = std::max(frame.max_residual, r.max_residual);
      if (!r.converged) {
        frame.converged = false;
        for (JointId j : r.violated()) {
          if (std::find(frame.violated.begin(), frame.violated.end(), j) == frame.violated.end())
            frame.violated.push_back(j);
        }
      }
      // Step 3: the speeds of the positions actually reached.
      std::vector<Speed> reached = speed;
      for (int i = 1; i < model.body_count(); ++i) {
        const Body& b = model.body(BodyId{i});
        if (b.fixed || !b.mass) continue;
        const Pose& p0 = before[static_cast<size_t>(i)];
        const Pose& p1 = trial[static_cast<size_t>(i)];
        Speed& s = reached[static_cast<size_t>(i)];
        s.v = (p1.apply(b.center) - p0.apply(b.center)) / h;
        s.w = rotation_vector_from_quat(p1.q * p0.q.conjugate()) / h;
      }
      if (!usable(trial, reached)) {
        frame.diverged = true;
        break;
      }
      speed = reached;
      poses = trial;
      t += h;
    }
    if (frame.diverged) {
      // Not kept: the model stays at the last good frame.
      out.converged = false;
      out.stopped = true;
      std::ostringstream w;
      w << "t = " << frame.time
        << ": diverged (a non-finite or out of range value); stopped at t = "
        << out.frames.back().time;
      out.warnings.push_back(w.str());
      break;
    }
    out.iterations += frame.iterations;
    out.max_residual = std::max(out.max_residual, frame.max_residual);
    frame.poses = poses;
    const bool ok = frame.converged;
    if (!ok) {
      out.converged = false;
      std::ostringstream w;
      w << "t = " << frame.time << ": the iteration cap was hit; still violated:";
      for (JointId j : frame.violated) {
        const Joint& jt = model.joint(j);
        w << " joint " << j.value << " (line " << jt.line << ", " << model.body(jt.body1).name
          << " / " << model.body(jt.body2).name << ")";
      }
      out.warnings.push_back(w.str());
    }
    out.frames.push_back(std::move(frame));
    if (!ok && o.stop_on_violation) {
      out.stopped = true;
      break;
    }
  }
  model.set_poses(poses);
  for (int i = 1; i < model.body_count(); ++i) {
    if (model.body(BodyId{i}).fixed) continue;
    model.set_speeds(BodyId{i}, speed[static_cast<size_t>(i)].v, speed[static_cast<size_t>(i)].w);
  }
  std::ostringstream msg;
  msg << "animated " << out.frames.back().time << " s in "
      << counted(static_cast<long long>(out.frames.size()) - 1, "frame") << ", "
      << counted(out.iterations, "iteration");
  if (!out.converged) msg << ", " << out.warnings.size() << " frames with violated constraints";
  if (out.stopped) msg << " (stopped)";
  out.message = msg.str();
  return out;
}

}  // namespace dispcon
