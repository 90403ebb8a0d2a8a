#include "dispcon/model/model.hpp"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dispcon {

namespace {

bool finite(const Vec3& v) {
  return v.allFinite();
}

void require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

Vec3 unit(const Vec3& v, const std::string& what) {
  require(finite(v), what + " is not finite");
  const double n = v.norm();
  require(n > 1e-300, what + " is a zero vector");
  return v / n;
}

void check_bounds(double& lo, double& hi, double natural_lo, double natural_hi,
                  const std::string& what) {
  require(!std::isnan(lo) && !std::isnan(hi), what + " bound is not a number");
  require(lo <= hi, what + ": min " + std::to_string(lo) + " is above max " + std::to_string(hi));
  lo = std::clamp(lo, natural_lo, natural_hi);
  hi = std::clamp(hi, natural_lo, natural_hi);
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
  require(finite(body.pose.x) && body.pose.q.coeffs().allFinite(), who + ": pose is not finite");
  require(body.pose.q.norm() > 1e-300, who + ": zero quaternion");
  body.pose.q.normalize();
  require(finite(body.center), who + ": center is not finite");
  if (body.rotate)
    require(std::isfinite(*body.rotate) && *body.rotate > 0,
            who + ": rotate must be a positive number");
  if (body.mass)
    require(std::isfinite(*body.mass) && *body.mass > 0, who + ": mass must be a positive number");
  if (body.inertia) {
    const Mat3& J = *body.inertia;
    require(J.allFinite(), who + ": inertia is not finite");
    require((J - J.transpose()).norm() <= 1e-12 * std::max(1.0, J.norm()),
            who + ": inertia is not symmetric");
    Eigen::LLT<Mat3> llt(J);
    require(llt.info() == Eigen::Success, who + ": inertia is not positive definite");
  }
  require(finite(body.velocity) && finite(body.spin) && finite(body.force) && finite(body.torque),
          who + ": velocity, spin, force or torque is not finite");
  const BodyId id{static_cast<int>(bodies_.size())};
  by_name_.emplace(body.name, id.value);
  bodies_.push_back(std::move(body));
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
  require(finite(j.p1) && finite(j.p2), who + ": hinge point is not finite");
  if (j.guide) {
    Guide& g = *j.guide;
    const std::string gw = who + ": " + to_string(g.kind);
    switch (g.kind) {
      case GuideKind::Point:
        break;
      case GuideKind::Axial:
        g.dir = unit(g.dir, gw + " direction");
        check_bounds(g.min, g.max, -kInf, kInf, gw);
        break;
      case GuideKind::Planar:
      case GuideKind::Sphere:
        if (g.kind == GuideKind::Planar) g.dir = unit(g.dir, gw + " normal");
        check_bounds(g.min, g.max, 0, kInf, gw);
        break;
      case GuideKind::Circle:
        g.dir = unit(g.dir, gw + " normal");
        require(std::isfinite(g.radius) && g.radius > 0, gw + " radius must be positive");
        break;
      case GuideKind::Cylinder:
        g.dir = unit(g.dir, gw + " axis");
        require(std::isfinite(g.radius) && g.radius >= 0, gw + " radius must not be negative");
        check_bounds(g.min, g.max, -kInf, kInf, gw);
        break;
      case GuideKind::Polyline:
        require(g.points.size() >= 2, gw + " needs at least two points");
        for (const Vec3& p : g.points) require(finite(p), gw + " point is not finite");
        break;
    }
  }
  if (j.angle) {
    j.angle->a1 = unit(j.angle->a1, who + ": angle vector a1");
    j.angle->a2 = unit(j.angle->a2, who + ": angle vector a2");
    check_bounds(j.angle->min, j.angle->max, 0, kPi, who + ": angle");
  }
  if (j.twist) {
    j.twist->b1 = unit(j.twist->b1, who + ": twist vector b1");
    j.twist->b2 = unit(j.twist->b2, who + ": twist vector b2");
    check_bounds(j.twist->min, j.twist->max, -kPi, kPi, who + ": twist");
  }
  if (j.move) require(*j.move >= 0 && *j.move <= 1, who + ": move must be in [0, 1]");
  require(!std::isnan(j.t0) && !std::isnan(j.t1) && j.t0 <= j.t1,
          who + ": time interval must have t0 <= t1");
  const JointId id{static_cast<int>(joints_.size())};
  joints_.push_back(std::move(j));
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
  for (size_t i = 1; i < bodies_.size(); ++i) bodies_[i].pose = poses[i];
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
