// The subcommands of `dispcon` (cli.md) and what they share: each one registers its options on
// the application and returns how to run it. Parsing and printing only; the work is the engine's.
#pragma once

#include <CLI/CLI.hpp>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon::cli {

// Exit codes (cli.md, "Exit codes").
constexpr int kOk = 0;
constexpr int kBadInput = 2;
constexpr int kViolated = 3;

// The file and options every subcommand takes.
struct Common {
  std::string file;
  double tolerance = SolveOptions{}.tolerance;  // the engine's defaults, stated there once
  int max_iterations = SolveOptions{}.max_iterations;
  bool json = false;
};

// A registered subcommand and how to run it once the arguments are parsed.
struct Subcommand {
  CLI::App* app = nullptr;
  std::function<int()> run;
};

Subcommand add_assemble(CLI::App& app);
Subcommand add_drag(CLI::App& app);
Subcommand add_animate(CLI::App& app);
Subcommand add_check(CLI::App& app);
Subcommand add_sweep(CLI::App& app);

// check, sweep, drag and assemble on a FreeCAD document (an argument ending in .FCStd and none in
// .dcl): handed to freecadcmd running the workbench.
bool is_fcstd_call(int argc, char** argv);
int run_fcstd(int argc, char** argv);

// FILE, --json and, for subcommands that solve, --tolerance and --max-iterations.
void add_common(CLI::App* sub, Common& common, bool solves = true);
SolveOptions options(const Common& common);
// Reads the file and prints its diagnostics (warnings too) on standard error; empty on errors.
std::optional<Model> load(const std::string& file);
// The body called `name`; bad usage (CLI::ValidationError) when there is none or it is the world.
BodyId body_named(const Model& model, const std::string& name);
Vec3 vec(const std::vector<double>& v);
// Writes `text` to `path`; false, with a message on standard error, when it cannot.
bool write_text(const std::string& path, const std::string& text);
// Flushes and closes a file written in pieces; false, with a message, when any write failed.
bool written(std::ofstream& out, const std::string& path);

}  // namespace dispcon::cli
