// `dispcon assemble`: the automatic search of valid initial positions (seed section 2.3).
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "dispcon/io/dcl_writer.hpp"
#include "report.hpp"

namespace dispcon::cli {
namespace {

struct AssembleArgs {
  Common common;
  std::string write;
};

// The model read, kept to the process's end: the command exits right after it, and the exit hands
// the whole heap back at once, where the model's destruction handed back its blocks one by one
// (0.27 M instructions for the 400 four-bars).
std::optional<Model>* kept_model = nullptr;

int run_assemble(const AssembleArgs& a) {
  kept_model = new std::optional<Model>(load(a.common.file));
  std::optional<Model>& m = *kept_model;
  if (!m) return kBadInput;
  const SolveResult r = assemble(*m, options(a.common));
  if (!a.write.empty() && r.converged && !write_text(a.write, write_dcl(*m))) return kBadInput;
  if (a.common.json) {
    print_json([&](JsonWriter& w) { write_object(w, solve_members(*m, r)); });
  } else {
    std::cout << a.common.file << ": ";
    print_solve(std::cout, *m, r);
    print_poses(std::cout, *m, r.poses);
    if (!a.write.empty() && r.converged) std::cout << "wrote " << a.write << "\n";
  }
  return r.converged ? kOk : kViolated;
}

}  // namespace

Subcommand add_assemble(CLI::App& app) {
  auto args = std::make_shared<AssembleArgs>();
  CLI::App* sub = app.add_subcommand("assemble", "move the objects until every constraint holds");
  add_common(sub, args->common);
  sub->add_option("--write", args->write, "save the assembled positions as a .dcl file");
  return {sub, [args] { return run_assemble(*args); }};
}

}  // namespace dispcon::cli
