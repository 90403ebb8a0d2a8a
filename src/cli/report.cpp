#include "report.hpp"

#include <cstdio>
#include <iomanip>

namespace dispcon::cli {

nlohmann::json pose_json(const Pose& pose) {
  const Mat3 R = pose.rotation();
  nlohmann::json rotation = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) rotation.push_back({R(i, 0), R(i, 1), R(i, 2)});
  Quat q = pose.q.normalized();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return {{"position", {pose.x.x(), pose.x.y(), pose.x.z()}},
          {"rotation", rotation},
          {"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
}

nlohmann::json bodies_json(const Model& model, const std::vector<Pose>& poses) {
  nlohmann::json out = nlohmann::json::object();
  for (int i = 1; i < model.body_count(); ++i) {
    out[model.body(BodyId{i}).name] = pose_json(poses[static_cast<size_t>(i)]);
  }
  return out;
}

nlohmann::json constraints_json(const Model& model, const std::vector<ConstraintReport>& reports) {
  nlohmann::json out = nlohmann::json::array();
  for (const ConstraintReport& c : reports) {
    const Joint& j = model.joint(c.joint);
    out.push_back({{"index", c.joint.value},
                   {"line", c.line},
                   {"object1", model.body(j.body1).name},
                   {"object2", model.body(j.body2).name},
                   {"residual", c.residual},
                   {"satisfied", c.satisfied},
                   {"active", c.active},
                   {"at_limit", c.at_limit}});
  }
  return out;
}

nlohmann::json solve_json(const Model& model, const SolveResult& r) {
  return {{"converged", r.converged},
          {"status", to_string(r.status)},
          {"iterations", r.iterations},
          {"seed_iterations", r.seed_iterations},
          {"newton_iterations", r.polish_iterations},
          {"max_residual", r.max_residual},
          {"message", r.message},
          {"bodies", bodies_json(model, r.poses)},
          {"constraints", constraints_json(model, r.constraints)}};
}

void csv_rows(std::ostream& out, const std::string& first, const Model& model,
              const std::vector<Pose>& poses) {
  char buf[512];
  for (int i = 1; i < model.body_count(); ++i) {
    const Pose& p = poses[static_cast<size_t>(i)];
    Quat q = p.q.normalized();
    if (q.w() < 0) q.coeffs() = -q.coeffs();
    std::snprintf(buf, sizeof buf, ",%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", p.x.x(), p.x.y(),
                  p.x.z(), q.w(), q.x(), q.y(), q.z());
    out << first << "," << model.body(BodyId{i}).name << buf << "\n";
  }
}

void print_poses(std::ostream& out, const Model& model, const std::vector<Pose>& poses) {
  out << "  " << std::left << std::setw(16) << "body" << std::setw(40) << "position"
      << "rotation vector\n";
  char buf[160];
  // Fixed point for the sizes of mechanisms; beyond a million, exponent form (1e+150 is not
  // written with 150 digits).
  auto fixed = [](const Vec3& v) { return (v.cwiseAbs().maxCoeff() < 1e6); };
  for (int i = 1; i < model.body_count(); ++i) {
    const Pose& p = poses[static_cast<size_t>(i)];
    const Vec3 r = p.rotation_vector();
    std::snprintf(buf, sizeof buf,
                  fixed(p.x) ? "%11.6f %11.6f %11.6f       %10.6f %10.6f %10.6f"
                             : "%11.5g %11.5g %11.5g       %10.6f %10.6f %10.6f",
                  p.x.x(), p.x.y(), p.x.z(), r.x(), r.y(), r.z());
    out << "  " << std::left << std::setw(16) << model.body(BodyId{i}).name << buf << "\n";
  }
}

void print_solve(std::ostream& out, const Model& model, const SolveResult& r) {
  out << r.message << "\n";
  if (!r.converged) {
    out << "violated constraints:\n";
    for (const ConstraintReport& c : r.constraints) {
      if (c.satisfied) continue;
      const Joint& j = model.joint(c.joint);
      out << "  #" << c.joint.value << " (line " << c.line << ") " << model.body(j.body1).name
          << " / " << model.body(j.body2).name << ": residual " << c.residual << "\n";
    }
  }
}

}  // namespace dispcon::cli
