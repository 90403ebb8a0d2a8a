#include "dispcon/model/model.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dispcon {

namespace {

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

// A bound pair: each bound a number within range or an infinity (no bound); min not above max;
// then clamped into the natural range of the quantity.
void check_bounds(double& lo, double& hi, double natural_lo, double natural_hi,
                  const std::string& field, const std::string& what) {
  auto one = [&](double v, const char* which) {
    if (!std::isinf(v)) check_number(v, field, what + " " + which);
  };
  one(lo, "min");
  one(hi, "max");
  if (lo > hi) {
    throw ValueError(field,
                     what + ": min " + format_number(lo) + " is above max " + format_number(hi));
  }
  lo = std::clamp(lo, natural_lo, natural_hi);
  hi = std::clamp(hi, natural_lo, natural_hi);
}

void check_inertia(const Mat3& J, const std::string& who) {
  for (int i = 0; i < 9; ++i) check_number(J.data()[i], "inertia", who + ": inertia");
  if ((J - J.transpose()).norm() > 1e-12 * std::max(1.0, J.norm()))
    throw ValueError("inertia", who + ": inertia is not symmetric");
  // Its principal moments: positive (positive definite) and within range, since the solver
  // inverts it.
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(J, Eigen::EigenvaluesOnly);
  const Vec3 moments = eig.eigenvalues();
  if (!(moments.minCoeff() > 0))
    throw ValueError("inertia", who + ": inertia is not positive definite");
  check_positive(moments.minCoeff(), "inertia", who + ": smallest principal inertia");
  check_positive(moments.maxCoeff(), "inertia", who + ": largest principal inertia");
}

}  // namespace

const char* to_string(GuideKind kind) {
  switch (kind) {
    case GuideKind::Point:
      return "point";
    case GuideKind::Axial:
      return "axial";
    case GuideKind::Planar:
      return "planar";
    case GuideKind::Sphere:
      return "sphere";
    case GuideKind::Circle:
      return "circle";
    case GuideKind::Cylinder:
      return "cylinder";
    case GuideKind::Polyline:
      return "polyline";
  }
  return "?";
}

Model::Model() {
  Body world;
  world.name = "world";
  world.fixed = true;
  bodies_.push_back(world);
  by_name_.emplace("world", 0);
}

BodyId Model::add_body(Body body) {
  const std::string who = "object '" + body.name + "'";
  require(!body.name.empty(), "an object needs a name");
  require(body.name != "world", "'world' is reserved for the fixed world frame");
  require(by_name_.count(body.name) == 0, "duplicate object '" + body.name + "'");
  body.pose = check_pose(body.pose, "position", who);
  check_vector(body.center, "center", who + ": center");
  if (body.rotate) check_positive(*body.rotate, "rotate", who + ": rotate");
  if (body.mass) check_positive(*body.mass, "mass", who + ": mass");
  if (body.inertia) check_inertia(*body.inertia, who);
  check_vector(body.velocity, "velocity", who + ": velocity");
  check_vector(body.spin, "spin", who + ": spin");
  check_vector(body.force, "force", who + ": force");
  check_vector(body.torque, "torque", who + ": torque");
  const BodyId id{static_cast<int>(bodies_.size())};
  by_name_.emplace(body.name, id.value);
  bodies_.push_back(std::move(body));
  ++revision_;
  return id;
}

JointId Model::add_joint(Joint j) {
  const std::string who = "constraint" + (j.line ? " at line " + std::to_string(j.line) : "");
  auto valid = [&](BodyId b) { return b.value >= 0 && b.value < body_count(); };
  require(valid(j.body1), who + ": object1 is not a body of the model");
  require(valid(j.body2), who + ": object2 is not a body of the model");
  require(j.body1 != j.body2,
          who + ": object1 and object2 are the same object '" + body(j.body1).name + "'");
  require(j.has_translation() || j.angle.has_value(),
          who + ": a constraint needs a hinge, a translation guide or an angle");
  require(!j.twist || j.angle, who + ": twist needs an angle (it uses the angle's axes)");
  check_vector(j.p1, "hinge", who + ": hinge P1");
  check_vector(j.p2, "hinge", who + ": hinge P2");
  if (j.guide) {
    Guide& g = *j.guide;
    const std::string field = to_string(g.kind);
    const std::string gw = who + ": " + field;
    switch (g.kind) {
      case GuideKind::Point:
        break;
      case GuideKind::Axial:
        g.dir = check_direction(g.dir, field, gw + " direction");
        check_bounds(g.min, g.max, -kInf, kInf, field, gw);
        break;
      case GuideKind::Planar:
      case GuideKind::Sphere:
        if (g.kind == GuideKind::Planar) g.dir = check_direction(g.dir, field, gw + " normal");
        check_bounds(g.min, g.max, 0, kInf, field, gw);
        break;
      case GuideKind::Circle:
        g.dir = check_direction(g.dir, field, gw + " normal");
        check_number(g.radius, field, gw + " radius");
        if (!(g.radius > 0)) throw ValueError(field, gw + " radius must be positive");
        break;
      case GuideKind::Cylinder:
        g.dir = check_direction(g.dir, field, gw + " axis");
        check_number(g.radius, field, gw + " radius");
        if (!(g.radius >= 0)) throw ValueError(field, gw + " radius must not be negative");
        check_bounds(g.min, g.max, -kInf, kInf, field, gw);
        break;
      case GuideKind::Polyline:
        if (g.points.size() < 2) throw ValueError(field, gw + " needs at least two points");
        for (const Vec3& p : g.points) check_vector(p, field, gw + " point");
        break;
    }
  }
  if (j.angle) {
    j.angle->a1 = check_direction(j.angle->a1, "angle", who + ": angle vector a1");
    j.angle->a2 = check_direction(j.angle->a2, "angle", who + ": angle vector a2");
    check_bounds(j.angle->min, j.angle->max, 0, kPi, "angle", who + ": angle");
  }
  if (j.twist) {
    j.twist->b1 = check_direction(j.twist->b1, "twist", who + ": twist vector b1");
    j.twist->b2 = check_direction(j.twist->b2, "twist", who + ": twist vector b2");
    check_bounds(j.twist->min, j.twist->max, -kPi, kPi, "twist", who + ": twist");
  }
  if (j.move && !(*j.move >= 0 && *j.move <= 1))
    throw ValueError("move", who + ": move " + format_number(*j.move) + " is not in [0, 1]");
  if (std::isnan(j.t0) || std::isnan(j.t1) || !(j.t0 <= j.t1))
    throw ValueError("time", who + ": time interval must have t0 <= t1");
  const JointId id{static_cast<int>(joints_.size())};
  joints_.push_back(std::move(j));
  ++revision_;
  return id;
}

std::optional<BodyId> Model::find(std::string_view name) const {
  auto it = by_name_.find(std::string(name));
  if (it == by_name_.end()) return std::nullopt;
  return BodyId{it->second};
}

std::vector<Pose> Model::poses() const {
  std::vector<Pose> out;
  out.reserve(bodies_.size());
  for (const Body& b : bodies_) out.push_back(b.pose);
  return out;
}

void Model::set_poses(const std::vector<Pose>& poses) {
  require(poses.size() == bodies_.size(), "set_poses: one pose per body expected");
  std::vector<Pose> checked(poses.size());
  for (size_t i = 1; i < bodies_.size(); ++i)
    checked[i] = check_pose(poses[i], "position", "object '" + bodies_[i].name + "'");
  for (size_t i = 1; i < bodies_.size(); ++i) bodies_[i].pose = checked[i];
}

Body& Model::movable_body(BodyId id, const char* what) {
  if (id.value <= 0 || id.value >= body_count()) {
    throw std::invalid_argument(std::string(what) + ": " +
                                (id == kWorld ? "the world cannot change" : "no such body"));
  }
  return bodies_[static_cast<size_t>(id.value)];
}

void Model::set_pose(BodyId id, const Pose& pose) {
  Body& b = movable_body(id, "set_pose");
  b.pose = check_pose(pose, "position", "object '" + b.name + "'");
}

void Model::set_speeds(BodyId id, const Vec3& velocity, const Vec3& spin) {
  Body& b = movable_body(id, "set_speeds");
  check_vector(velocity, "velocity", "object '" + b.name + "': velocity");
  check_vector(spin, "spin", "object '" + b.name + "': spin");
  b.velocity = velocity;
  b.spin = spin;
}

void Model::set_fixed(BodyId id, bool fixed) {
  movable_body(id, "set_fixed").fixed = fixed;
  ++revision_;
}

void Model::set_mass(BodyId id, std::optional<double> mass) {
  Body& b = movable_body(id, "set_mass");
  if (mass) check_positive(*mass, "mass", "object '" + b.name + "': mass");
  b.mass = mass;
  ++revision_;
}

void Model::set_rotate(BodyId id, std::optional<double> rotate) {
  Body& b = movable_body(id, "set_rotate");
  if (rotate) check_positive(*rotate, "rotate", "object '" + b.name + "': rotate");
  b.rotate = rotate;
  ++revision_;
}

void Model::set_hinge(JointId id, const std::optional<Vec3>& p1, const std::optional<Vec3>& p2) {
  if (id.value < 0 || id.value >= joint_count())
    throw std::invalid_argument("no joint " + std::to_string(id.value));
  Joint& j = joints_[static_cast<size_t>(id.value)];
  const std::string who = "joint " + std::to_string(id.value);
  if (!j.has_hinge) throw std::invalid_argument(who + " has no hinge");
  if (p1) check_vector(*p1, "hinge", who + ": hinge P1");
  if (p2) check_vector(*p2, "hinge", who + ": hinge P2");
  if (p1) j.p1 = *p1;
  if (p2) j.p2 = *p2;
}

void Model::set_twist_range(JointId id, double min, double max) {
  if (id.value < 0 || id.value >= joint_count())
    throw std::invalid_argument("no joint " + std::to_string(id.value));
  Joint& j = joints_[static_cast<size_t>(id.value)];
  const std::string who = "joint " + std::to_string(id.value);
  if (!j.twist) throw std::invalid_argument(who + " has no twist");
  check_bounds(min, max, -kPi, kPi, "twist", who + ": twist");
  j.twist->min = min;
  j.twist->max = max;
}

double Model::ability_to_rotate(BodyId id) const {
  return abilities_to_rotate().at(static_cast<size_t>(id.value));
}

std::vector<double> Model::abilities_to_rotate() const {
  std::vector<double> sum(bodies_.size(), 0.0);
  std::vector<int> count(bodies_.size(), 0);
  auto add = [&](BodyId id, const Vec3& p) {
    const size_t i = static_cast<size_t>(id.value);
    sum[i] += (p - bodies_[i].center).squaredNorm();
    ++count[i];
  };
  for (const Joint& j : joints_) {
    if (!j.has_translation()) continue;
    if (j.guide && j.guide->kind == GuideKind::Polyline) {
      for (const Vec3& p : j.guide->points) add(j.body1, p);
    } else {
      add(j.body1, j.p1);
    }
    add(j.body2, j.p2);
  }
  std::vector<double> k(bodies_.size(), 1.0);
  for (size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_[i].rotate) {
      k[i] = *bodies_[i].rotate;
    } else if (count[i] > 0 && sum[i] > 0) {
      k[i] = count[i] / sum[i];  // 1 / rho^2, rho the RMS distance
    }
  }
  return k;
}

double Model::move_share(JointId id) const {
  const Joint& j = joint(id);
  const Body& b1 = body(j.body1);
  const Body& b2 = body(j.body2);
  if (b1.fixed) return 0.0;
  if (b2.fixed) return 1.0;
  if (j.move) return *j.move;
  if (b1.mass && b2.mass) return *b2.mass / (*b1.mass + *b2.mass);
  return 0.5;
}

}  // namespace dispcon
