#include "dispcon/solve/report.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace dispcon {

std::string describe(const Model& model, const ConstraintReport& c) {
  const Joint& j = model.joint(c.joint);
  std::ostringstream out;
  out << "joint " << c.joint.value;
  if (c.line) out << " (line " << c.line << ")";
  out << " " << model.body(j.body1).name << " / " << model.body(j.body2).name;
  if (j.coupling) out << " (" << to_string(j.coupling->kind) << ")";
  out << " residual " << c.residual;
  return out.str();
}

std::vector<ConstraintReport> report(const SolverState& s, double tolerance,
                                     const std::vector<double>* known) {
  std::vector<ConstraintReport> out;
  out.reserve(s.joints.size());
  for (size_t c = 0; c < s.joints.size(); ++c) {
    const JointState& js = s.joints[c];
    ConstraintReport r;
    r.joint = JointId{static_cast<int>(c)};
    r.line = js.joint->line;
    r.active = js.active;
    r.residual = known ? (*known)[c] : s.residual(js);
    r.satisfied = r.residual <= tolerance;
    r.at_limit = js.active && js.bounded && s.at_limit(js, contact_band(tolerance));
    out.push_back(r);
  }
  return out;
}

std::vector<ConstraintReport> violated_worst_first(const std::vector<ConstraintReport>& all) {
  std::vector<ConstraintReport> bad;
  for (const ConstraintReport& c : all) {
    if (!c.satisfied) bad.push_back(c);
  }
  // Non-finite first (a NaN compares false, so it is ranked as infinite).
  auto key = [](double r) { return std::isnan(r) ? std::numeric_limits<double>::infinity() : r; };
  std::stable_sort(bad.begin(), bad.end(),
                   [&](const ConstraintReport& a, const ConstraintReport& b) {
                     return key(a.residual) > key(b.residual);
                   });
  return bad;
}

std::string counted(long long n, const char* word) {
  return std::to_string(n) + " " + word + (n == 1 ? "" : "s");
}

std::string solve_message(const Model& model, const SolveResult& result) {
  std::ostringstream msg;
  if (result.converged) {
    msg << "converged in " << counted(result.iterations, "iteration") << " (max residual "
        << result.max_residual << ")";
    return msg.str();
  }
  if (result.status == SolveStatus::Diverged) {
    msg << "diverged after " << counted(result.iterations, "iteration")
        << " (a residual or a pose became infinite or not a number; the poses were "
           "not changed); at fault: ";
  } else {
    msg << "did not converge after " << counted(result.iterations, "iteration")
        << (result.status == SolveStatus::Stalled
                ? " (no progress: over-constrained or unreachable)"
                : "")
        << "; still violated: ";
  }
  const std::vector<ConstraintReport> bad = violated_worst_first(result.constraints);
  for (size_t k = 0; k < bad.size() && k < 5; ++k) {
    msg << (k ? "; " : "") << describe(model, bad[k]);
  }
  if (bad.empty()) msg << "no joint (a body's pose)";
  if (bad.size() > 5) msg << "; and " << bad.size() - 5 << " more";
  return msg.str();
}

}  // namespace dispcon
