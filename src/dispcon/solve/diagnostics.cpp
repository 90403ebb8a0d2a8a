// Diagnostics at the assembled pose: degrees of freedom from the rank of the constraints'
// Jacobian (SVD, group by group: rank.cpp), redundant joints (equations that repeat others),
// conflicting joints (whose removal lets the rest assemble), limits in contact, and range-of-motion
// sweeps.
#include "dispcon/solve/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "dispcon/parts/angle.hpp"
#include "dispcon/parts/nearest.hpp"
#include "dispcon/parts/twist.hpp"
#include "dispcon/solve/group.hpp"
#include "dispcon/solve/rank.hpp"
#include "dispcon/solve/report.hpp"
#include "dispcon/solve/state.hpp"

namespace dispcon {

namespace {

// Every body (the same ids) and the joints `keep(c)` accepts.
template <typename Keep>
Model with_joints(const Model& model, Keep keep) {
  Model m;
  for (int i = 1; i < model.body_count(); ++i) m.add_body(model.body(BodyId{i}));
  for (int c = 0; c < model.joint_count(); ++c) {
    if (keep(c)) m.add_joint(model.joint(JointId{c}));
  }
  return m;
}

// The group of bodies each joint belongs to (find_groups' index); -1 for an active joint between
// two bodies that cannot move, -2 for an inactive joint.
std::vector<int> group_of_joints(const Model& model, const SolveOptions& options) {
  const SolverState s(model, model.poses(), options, {});
  std::vector<int> out(s.joints.size(), -1);
  for (size_t c = 0; c < s.joints.size(); ++c) {
    if (!s.joints[c].active) out[c] = -2;
  }
  const std::vector<Group> groups = find_groups(s);
  for (size_t g = 0; g < groups.size(); ++g) {
    for (int c : groups[g].joints) out[static_cast<size_t>(c)] = static_cast<int>(g);
  }
  return out;
}

// The model with the limits of the joints in `at_limit` let go: a range (a guide's travel, a
// cone, a turn's limits) opened, the equalities kept (a range whose min is its max is one). At a
// limit a mechanism is held by the limit, not locked by its couplings.
Model released(const Model& model, const std::vector<JointId>& at_limit) {
  Model m;
  for (int i = 1; i < model.body_count(); ++i) m.add_body(model.body(BodyId{i}));
  for (int c = 0; c < model.joint_count(); ++c) {
    Joint j = model.joint(JointId{c});
    if (std::find(at_limit.begin(), at_limit.end(), JointId{c}) != at_limit.end()) {
      if (j.guide && j.guide->min < j.guide->max) j.guide->min = -kInf, j.guide->max = kInf;
      if (j.twist && j.twist->min < j.twist->max) j.twist.reset();
      if (j.angle && !j.twist && j.angle->min < j.angle->max) j.angle.reset();
    }
    m.add_joint(j);
  }
  return m;
}

std::string joint_name(const Model& model, JointId id) {
  const Joint& j = model.joint(id);
  std::ostringstream out;
  out << "joint #" << id.value;
  if (j.line) out << " (line " << j.line << ")";
  out << " " << model.body(j.body1).name << " / " << model.body(j.body2).name;
  return out.str();
}

}  // namespace

CheckResult check(const Model& input, const SolveOptions& options) {
  CheckResult out;
  Model model = input;
  out.solve = assemble(model, options);
  for (const ConstraintReport& c : out.solve.constraints) {
    if (c.at_limit) out.limits_active.push_back(c.joint);
  }

  // Conflicting: when the assembly fails, find the joint whose removal lets the rest assemble,
  // trying the most violated first.
  int removed = -1;
  if (!out.solve.converged) {
    // A NaN residual ranks first (and cannot break the sort's ordering); ties keep file order.
    const std::vector<ConstraintReport> bad = violated_worst_first(out.solve.constraints);
    SolveOptions o = options;
    o.max_iterations = std::min(options.max_iterations, 2000);
    // Groups of bodies solve independently: a removal can only mend the group it is in, so when
    // the violated joints lie in several groups no single removal can help, and a removal is
    // tried on its group alone. Only a removal that mends its group is tried on the whole model.
    const std::vector<int> group = group_of_joints(input, options);
    bool one_group = true;
    for (const ConstraintReport& c : bad) {
      one_group = one_group && group[static_cast<size_t>(c.joint.value)] ==
                                   group[static_cast<size_t>(bad[0].joint.value)];
    }
    for (size_t k = 0; one_group && k < bad.size(); ++k) {
      const JointId c = bad[k].joint;
      const int g = group[static_cast<size_t>(c.value)];
      // The group alone, the other bodies free (they cost nothing), then the whole model.
      Model part = with_joints(
          input, [&](int j) { return j != c.value && group[static_cast<size_t>(j)] == g; });
      if (!assemble(part, o).converged) continue;
      Model trial = with_joints(input, [&](int j) { return j != c.value; });
      if (assemble(trial, o).converged) {
        removed = c.value;
        model = trial;
        out.conflicting.push_back(c);
        out.advice.push_back("removing " + joint_name(input, c) + " makes the model consistent");
        break;
      }
    }
    if (out.conflicting.empty()) {
      for (const ConstraintReport& c : bad) out.conflicting.push_back(c.joint);
      out.advice.push_back(
          "no single joint's removal makes the model consistent; the violated "
          "joints are listed as conflicting");
    }
  }

  // Degrees of freedom and redundancy at the assembled pose, group by group; when a conflicting
  // joint was found, of the consistent model without it (joint numbers stay those of the input).
  auto to_input = [&](int c) { return removed >= 0 && c >= removed ? c + 1 : c; };
  RankReport rank = rank_by_group(model, options);
  out.dof = rank.dof;
  out.body_dof = std::move(rank.body_dof);
  for (const Repeated& r : rank.redundant) {
    const JointId id{to_input(r.joint.value)};
    out.redundant.push_back(id);
    std::ostringstream a;
    a << joint_name(input, id) << ": " << r.repeated << " of its " << r.equations
      << " equations repeat those of the joints before it; the model stays consistent and "
         "keeps its mobility without them (for a planar linkage modelled in 3D, make one of "
         "its revolutes a point-to-point joint)";
    out.advice.push_back(a.str());
  }

  // Locked by its couplings (two gear paths with different ratios): with no freedom left, the
  // couplings whose removal frees the mechanism. Its limits in contact let go first: a gear at
  // its turn's limit has no freedom left either, which its mesh is not to blame for (the fourth
  // audit's wheel at its limit named its two meshes as locking the train).
  if (out.dof == 0) {
    const bool held = removed < 0 && !out.limits_active.empty();
    const Model unlimited = held ? released(model, out.limits_active) : Model{};
    const Model& free = held ? unlimited : model;
    if (!held || rank_by_group(free, options).dof == 0) {
      for (int c = 0; c < free.joint_count(); ++c) {
        if (!free.joint(JointId{c}).coupling) continue;
        const Model freed = with_joints(free, [c](int k) { return k != c; });
        if (rank_by_group(freed, options).dof > 0) out.locking.push_back(JointId{to_input(c)});
      }
    }
    if (!out.locking.empty()) {
      std::ostringstream a;
      a << "the couplings lock the mechanism (gear paths with different ratios?): removing one of ";
      for (size_t k = 0; k < out.locking.size(); ++k) {
        a << (k ? ", " : "") << joint_name(input, out.locking[k]);
      }
      a << " frees it";
      out.advice.push_back(a.str());
    }
  }

  std::ostringstream msg;
  if (out.solve.converged) {
    msg << "assembled; " << counted(out.dof, "degree") << " of freedom";
  } else {
    msg << "does not assemble (" << out.solve.message << ")";
  }
  const auto n = [](const auto& list) { return static_cast<long long>(list.size()); };
  if (!out.redundant.empty()) msg << ", " << counted(n(out.redundant), "redundant joint");
  if (!out.conflicting.empty()) msg << ", " << counted(n(out.conflicting), "conflicting joint");
  if (!out.limits_active.empty())
    msg << ", " << counted(n(out.limits_active), "limit") << " in contact";
  if (!out.locking.empty()) msg << ", locked by " << counted(n(out.locking), "coupling");
  out.message = msg.str();
  return out;
}

namespace {

// A joint's value: the relative turn about a revolute's axis since the start, the angle of an
// angle part with a range, or the travel along a segment or cylinder; NaN otherwise.
struct JointGauge {
  enum Kind { None, Turn, Angle, Travel, Radius } kind = None;
  Vec3 b1 = Vec3::Zero(), b2 = Vec3::Zero();  // Turn: references, local to each body
  double offset = 0;

  static JointGauge make(const Model& m, const Joint& j) {
    JointGauge g;
    if (j.angle && j.angle->max == 0) {
      g.kind = Turn;
      g.b1 = any_perpendicular(j.angle->a1);
      const Mat3 R1 = m.body(j.body1).pose.rotation();
      const Mat3 R2 = m.body(j.body2).pose.rotation();
      g.b2 = R2.transpose() * R1 * g.b1;
    } else if (j.angle) {
      g.kind = Angle;
    } else if (j.guide &&
               (j.guide->kind == GuideKind::Axial || j.guide->kind == GuideKind::Cylinder)) {
      g.kind = Travel;
    } else if (j.guide &&
               (j.guide->kind == GuideKind::Planar || j.guide->kind == GuideKind::Sphere)) {
      g.kind = Radius;
    }
    return g;
  }

  double value(const std::vector<Pose>& poses, const Joint& j) const {
    const Pose& p1 = poses[static_cast<size_t>(j.body1.value)];
    const Pose& p2 = poses[static_cast<size_t>(j.body2.value)];
    switch (kind) {
      case Turn: {
        const Vec3 a = p1.q * j.angle->a1;
        return twist_angle(a, a, p1.q * b1, p2.q * b2);
      }
      case Angle:
        return angle_between(p1.q * j.angle->a1, p2.q * j.angle->a2);
      case Travel:
        return (p1.q.conjugate() * (p2.apply(j.p2) - p1.x) - j.p1).dot(j.guide->dir);
      case Radius: {
        Vec3 d = p1.q.conjugate() * (p2.apply(j.p2) - p1.x) - j.p1;
        if (j.guide->kind == GuideKind::Planar) d -= d.dot(j.guide->dir) * j.guide->dir;
        return d.norm();
      }
      case None:
        break;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }
};

}  // namespace

void validate(const SweepOptions& o) {
  check_direction(o.axis, "axis", "sweep: axis");
  check_number(o.from, "from", "sweep: from");
  check_number(o.to, "to", "sweep: to");
  if (o.steps < 1 || o.steps > kMaxSweepSteps) {
    throw ValueError("steps", "sweep: steps " + std::to_string(o.steps) + " is not in [1, " +
                                  std::to_string(kMaxSweepSteps) + "]");
  }
  validate(o.solve);
}

SweepResult sweep(const Model& input, const SweepOptions& o) {
  validate(o);
  SweepResult out;
  Model model = input;
  if (o.body.value <= 0 || o.body.value >= model.body_count()) {
    throw std::invalid_argument("sweep: unknown body");
  }
  const SolveResult first = assemble(model, o.solve);
  if (!first.converged) {
    out.locked = true;
    out.lock_value = o.from;
    out.message = "the model does not assemble: " + first.message;
    return out;
  }
  // The driver: a joint from the world to the body whose twist about the axis is set to each
  // value in turn (its angle part is left free), so the body is driven about the axis while
  // everything else about it stays free: an axis given to a few digits cannot over-constrain it.
  const Vec3 axis = check_direction(o.axis, "axis", "sweep: axis");
  const Mat3 R0 = model.body(o.body).pose.rotation();
  Joint driver;
  driver.body1 = Model::kWorld;
  driver.body2 = o.body;
  driver.angle = AngleSpec{axis, R0.transpose() * axis, 0, kPi};
  const Vec3 b = any_perpendicular(axis);
  driver.twist = TwistSpec{b, R0.transpose() * b, 0, 0};
  driver.label = "sweep driver";
  std::vector<JointGauge> gauges;
  for (const Joint& j : model.joints()) gauges.push_back(JointGauge::make(model, j));
  const int n_joints = model.joint_count();
  const JointId driver_id = model.add_joint(driver);
  Session session(model, o.solve);
  auto drive = [&](double value) {
    const double turn = std::remainder(value, 2 * kPi);
    model.set_twist_range(driver_id, turn, turn);
    std::vector<Pose> poses = model.poses();
    SolveResult r = session.solve(poses);
    if (r.converged) model.set_poses(poses);
    return r;
  };
  auto sample = [&](double value, const SolveResult& r) {
    SweepSample s;
    s.value = value;
    s.converged = r.converged;
    s.max_residual = r.max_residual;
    s.poses = model.poses();
    for (const ConstraintReport& c : r.constraints) {
      if (c.at_limit && c.joint.value < n_joints) s.limits_active.push_back(c.joint);
    }
    for (size_t j = 0; j < gauges.size(); ++j) {
      s.joint_values.push_back(gauges[j].value(s.poses, model.joint(JointId{static_cast<int>(j)})));
    }
    return s;
  };
  double last_good = o.from;
  for (int k = 0; k <= o.steps; ++k) {
    const double value = o.from + (o.to - o.from) * k / o.steps;
    const SolveResult r = drive(value);
    if (!r.converged) {
      // Bisect between the last value reached and this one: where exactly does it lock?
      double lo = last_good, hi = value;
      for (int i = 0; i < 30 && std::abs(hi - lo) > 1e-9; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (drive(mid).converged) {
          lo = mid;
        } else {
          hi = mid;
        }
      }
      out.locked = true;
      out.lock_value = lo;
      out.samples.push_back(sample(value, r));
      break;
    }
    last_good = value;
    out.samples.push_back(sample(value, r));
  }
  std::ostringstream msg;
  if (out.locked) {
    msg << "locks at " << out.lock_value << " rad (" << out.lock_value * 180 / kPi
        << " deg): no position reachable by continuity beyond it";
  } else {
    msg << "turns freely from " << o.from << " to " << o.to << " rad";
  }
  out.message = msg.str();
  return out;
}

}  // namespace dispcon
