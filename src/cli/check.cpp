// `dispcon check`: degrees of freedom, redundant and conflicting constraints, limits in contact.
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "dispcon/solve/diagnostics.hpp"
#include "report.hpp"

namespace dispcon::cli {
namespace {

int run_check(const Common& c) {
  auto m = load(c.file);
  if (!m) return kBadInput;
  const CheckResult r = check(*m, options(c));
  if (c.json) {
    std::vector<Member> doc = solve_members(*m, r.solve, &r.body_dof);
    doc.insert(doc.end(),
               {{"dof", [&](JsonWriter& w) { w.value(r.dof); }},
                {"redundant", [&](JsonWriter& w) { write_joint_list(w, r.redundant); }},
                {"conflicting", [&](JsonWriter& w) { write_joint_list(w, r.conflicting); }},
                {"limits_active", [&](JsonWriter& w) { write_joint_list(w, r.limits_active); }},
                {"locking", [&](JsonWriter& w) { write_joint_list(w, r.locking); }},
                {"advice", [&](JsonWriter& w) { write_strings(w, r.advice); }},
                {"diagnosis", [&](JsonWriter& w) { w.value(r.message); }}});
    print_json([&](JsonWriter& w) { write_object(w, std::move(doc)); });
  } else {
    std::cout << c.file << ": " << r.message << "\n";
    std::cout << "degrees of freedom: " << r.dof << "\n";
    for (int i = 1; i < m->body_count(); ++i) {
      std::cout << "  " << m->body(BodyId{i}).name << ": " << r.body_dof[static_cast<size_t>(i)]
                << "\n";
    }
    auto names = [&](const char* what, const std::vector<JointId>& ids) {
      if (ids.empty()) return;
      std::cout << what << ":";
      for (JointId j : ids) std::cout << " #" << j.value << " (line " << m->joint(j).line << ")";
      std::cout << "\n";
    };
    names("redundant", r.redundant);
    names("conflicting", r.conflicting);
    names("limits in contact", r.limits_active);
    names("locking couplings", r.locking);
    for (const std::string& a : r.advice) std::cout << a << "\n";
  }
  return r.solve.converged && r.conflicting.empty() ? kOk : kViolated;
}

}  // namespace

Subcommand add_check(CLI::App& app) {
  auto args = std::make_shared<Common>();
  CLI::App* sub =
      app.add_subcommand("check", "degrees of freedom, redundant and conflicting constraints");
  add_common(sub, *args);
  return {sub, [args] { return run_check(*args); }};
}

}  // namespace dispcon::cli
