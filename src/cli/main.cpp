// `dispcon`: the command line over .dcl files (cli.md). Parsing arguments and printing only; all
// the work is the engine's.
#include <CLI/CLI.hpp>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/io/dcl_writer.hpp"
#include "dispcon/io/svg.hpp"
#include "dispcon/io/sweep_plot.hpp"
#include "dispcon/solve/diagnostics.hpp"
#include "dispcon/solve/dynamics.hpp"
#include "dispcon/solve/solver.hpp"
#include "report.hpp"

namespace {

using namespace dispcon;
using nlohmann::json;

constexpr int kOk = 0;
constexpr int kBadInput = 2;
constexpr int kViolated = 3;

struct Common {
  std::string file;
  double tolerance = 1e-9;
  int max_iterations = 10000;
  bool json = false;
};

void add_common(CLI::App* sub, Common& c, bool solves = true) {
  sub->add_option("FILE", c.file, "the .dcl file")->required();
  if (solves) {
    sub->add_option("--tolerance", c.tolerance, "largest violation accepted (default 1e-9)")
        ->check(CLI::PositiveNumber);
    sub->add_option("--max-iterations", c.max_iterations, "iteration cap (default 10000)")
        ->check(CLI::PositiveNumber);
  }
  sub->add_flag("--json", c.json, "print one JSON document on standard output");
}

SolveOptions options(const Common& c) {
  SolveOptions o;
  o.tolerance = c.tolerance;
  o.max_iterations = c.max_iterations;
  return o;
}

// Reads the file; prints its diagnostics (warnings too) on standard error.
std::optional<Model> load(const std::string& file) {
  ParseResult r = load_dcl(file);
  std::cerr << r.messages();
  return std::move(r.model);
}

BodyId body_named(const Model& m, const std::string& name) {
  const auto id = m.find(name);
  if (!id || *id == Model::kWorld)
    throw CLI::ValidationError("--body", "unknown body '" + name + "'");
  return *id;
}

Vec3 vec(const std::vector<double>& v) {
  return Vec3(v[0], v[1], v[2]);
}

bool write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) std::cerr << path << ": error: cannot write the file\n";
  return static_cast<bool>(out);
}

int assemble_cmd(const Common& c, const std::string& write) {
  auto m = load(c.file);
  if (!m) return kBadInput;
  const SolveResult r = assemble(*m, options(c));
  if (!write.empty() && r.converged && !write_text(write, write_dcl(*m))) return kBadInput;
  if (c.json) {
    std::cout << cli::solve_json(*m, r).dump(2) << "\n";
  } else {
    std::cout << c.file << ": ";
    cli::print_solve(std::cout, *m, r);
    cli::print_poses(std::cout, *m, r.poses);
    if (!write.empty() && r.converged) std::cout << "wrote " << write << "\n";
  }
  return r.converged ? kOk : kViolated;
}

int drag_cmd(const Common& c, const std::string& name, const std::vector<double>& to,
             const std::vector<double>& rotation, int steps, const std::string& csv) {
  auto m = load(c.file);
  if (!m) return kBadInput;
  const BodyId body = body_named(*m, name);
  const SolveOptions o = options(c);
  const SolveResult first = assemble(*m, o);
  Pose target = m->body(body).pose;
  target.x = vec(to);
  if (!rotation.empty()) target.q = quat_from_rotation_vector(vec(rotation));
  std::vector<std::vector<Pose>> poses;
  DragResult d;
  if (first.converged) {
    d = drag(*m, body, target, steps, o, &poses);
  } else {
    d.converged = false;
    d.failed_step = 0;
    d.message = "the model does not assemble: " + first.message;
  }
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "step,body,px,py,pz,qw,qx,qy,qz\n";
    for (size_t k = 0; k < poses.size(); ++k)
      cli::csv_rows(out, std::to_string(k + 1), *m, poses[k]);
    if (!out) {
      std::cerr << csv << ": error: cannot write the file\n";
      return kBadInput;
    }
  }
  const std::vector<ConstraintReport> now =
      d.steps.empty() ? first.constraints : d.steps.back().constraints;
  if (c.json) {
    json steps_json = json::array();
    for (const SolveResult& s : d.steps) {
      steps_json.push_back({{"iterations", s.iterations},
                            {"max_residual", s.max_residual},
                            {"converged", s.converged}});
    }
    json doc = {{"converged", d.converged && first.converged},
                {"iterations", first.iterations + d.iterations},
                {"max_residual", std::max(first.max_residual, d.max_residual)},
                {"message", d.message},
                {"failed_step", d.failed_step},
                {"bodies", cli::bodies_json(*m, m->poses())},
                {"constraints", cli::constraints_json(*m, now)},
                {"steps", steps_json}};
    std::cout << doc.dump(2) << "\n";
  } else {
    std::cout << c.file << ": assembled: " << first.message << "\n" << d.message << "\n";
    if (!d.steps.empty()) {
      int worst = 0;
      for (const SolveResult& s : d.steps) worst = std::max(worst, s.iterations);
      std::cout << "iterations per step: mean "
                << (d.iterations - first.iterations) * 1.0 / d.steps.size() << ", worst " << worst
                << "\n";
    }
    cli::print_poses(std::cout, *m, m->poses());
  }
  return d.converged && first.converged ? kOk : kViolated;
}

int animate_cmd(const Common& c, double duration, double dt, const std::vector<double>& gravity,
                const std::string& csv, const std::string& svg, bool stop) {
  auto m = load(c.file);
  if (!m) return kBadInput;
  AnimateOptions a;
  a.duration = duration;
  a.dt = dt;
  if (!gravity.empty()) a.gravity = vec(gravity);
  a.stop_on_violation = stop;
  a.solve = options(c);
  const AnimateResult r = animate(*m, a);
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "time,body,px,py,pz,qw,qx,qy,qz\n";
    char t[64];
    for (const Frame& f : r.frames) {
      std::snprintf(t, sizeof t, "%.9g", f.time);
      cli::csv_rows(out, t, *m, f.poses);
    }
  }
  if (!svg.empty() && !write_text(svg, write_animation_svg(*m, r))) return kBadInput;
  const std::vector<ConstraintReport> now = measure(*m, m->poses(), a.solve);
  if (c.json) {
    json frames = json::array();
    for (const Frame& f : r.frames) {
      json violated = json::array();
      for (JointId j : f.violated) violated.push_back(j.value);
      frames.push_back({{"time", f.time},
                        {"iterations", f.iterations},
                        {"max_residual", f.max_residual},
                        {"converged", f.converged},
                        {"violated", violated}});
    }
    json doc = {{"converged", r.converged},
                {"stopped", r.stopped},
                {"iterations", r.iterations},
                {"max_residual", r.max_residual},
                {"message", r.message},
                {"warnings", r.warnings},
                {"bodies", cli::bodies_json(*m, m->poses())},
                {"constraints", cli::constraints_json(*m, now)},
                {"frames", frames}};
    std::cout << doc.dump(2) << "\n";
  } else {
    std::cout << c.file << ": " << r.message << "\n";
    for (const std::string& w : r.warnings) std::cerr << c.file << ": warning: " << w << "\n";
    cli::print_poses(std::cout, *m, m->poses());
  }
  return r.converged ? kOk : kViolated;
}

json joint_list(const std::vector<JointId>& ids) {
  json out = json::array();
  for (JointId j : ids) out.push_back(j.value);
  return out;
}

int check_cmd(const Common& c) {
  auto m = load(c.file);
  if (!m) return kBadInput;
  const CheckResult r = check(*m, options(c));
  if (c.json) {
    json doc = cli::solve_json(*m, r.solve);
    doc["dof"] = r.dof;
    doc["redundant"] = joint_list(r.redundant);
    doc["conflicting"] = joint_list(r.conflicting);
    doc["limits_active"] = joint_list(r.limits_active);
    doc["advice"] = r.advice;
    doc["diagnosis"] = r.message;
    for (int i = 1; i < m->body_count(); ++i) {
      doc["bodies"][m->body(BodyId{i}).name]["dof"] = r.body_dof[static_cast<size_t>(i)];
    }
    std::cout << doc.dump(2) << "\n";
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
    for (const std::string& a : r.advice) std::cout << a << "\n";
  }
  return r.solve.converged && r.conflicting.empty() ? kOk : kViolated;
}

int sweep_cmd(const Common& c, const std::string& name, const std::vector<double>& axis,
              double from, double to, int steps, const std::string& csv, const std::string& plot) {
  auto m = load(c.file);
  if (!m) return kBadInput;
  SweepOptions s;
  s.body = body_named(*m, name);
  s.axis = vec(axis);
  s.from = from;
  s.to = to;
  s.steps = steps;
  s.solve = options(c);
  const SweepResult r = sweep(*m, s);
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "value,converged,max_residual";
    for (int j = 0; j < m->joint_count(); ++j) out << ",joint" << j;
    out << "\n";
    for (const SweepSample& x : r.samples) {
      out << x.value << "," << (x.converged ? 1 : 0) << "," << x.max_residual;
      for (double v : x.joint_values) out << "," << v;
      out << "\n";
    }
  }
  if (!plot.empty() && !write_text(plot, write_sweep_svg(*m, r))) return kBadInput;
  if (c.json) {
    json samples = json::array();
    for (const SweepSample& x : r.samples) {
      samples.push_back({{"value", x.value},
                         {"converged", x.converged},
                         {"max_residual", x.max_residual},
                         {"limits_active", joint_list(x.limits_active)},
                         {"joint_values", x.joint_values}});
    }
    json doc = {{"converged", !r.locked},
                {"locked", r.locked},
                {"lock_value", r.lock_value},
                {"message", r.message},
                {"samples", samples}};
    std::cout << doc.dump(2) << "\n";
  } else {
    std::cout << c.file << ": " << r.message << "\n";
  }
  return r.locked ? kViolated : kOk;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "dispcon: mechanism assembly with displacement constraints (Gascuel & Gascuel 1994)"};
  app.require_subcommand(1);
  Common c;

  std::string write;
  CLI::App* assemble_sub =
      app.add_subcommand("assemble", "move the objects until every constraint holds");
  add_common(assemble_sub, c);
  assemble_sub->add_option("--write", write, "save the assembled positions as a .dcl file");

  std::string body, csv, svg, plot;
  std::vector<double> to, rotation, gravity, axis = {0, 0, 1};
  int steps = 50;
  CLI::App* drag_sub = app.add_subcommand("drag", "hold one body on a path while the rest follows");
  add_common(drag_sub, c);
  drag_sub->add_option("--body", body, "the body to move")->required();
  drag_sub->add_option("--to", to, "target position X Y Z")->required()->expected(3);
  drag_sub->add_option("--rotation", rotation, "target rotation vector RX RY RZ")->expected(3);
  drag_sub->add_option("--steps", steps, "number of equal steps (default 50)")
      ->check(CLI::PositiveNumber);
  drag_sub->add_option("--csv", csv, "write every step's poses");

  double duration = 1, dt = 0.01;
  bool stop = false;
  CLI::App* animate_sub =
      app.add_subcommand("animate", "the physics variant: integrate, constrain, correct speeds");
  add_common(animate_sub, c);
  animate_sub->add_option("--duration", duration, "seconds")
      ->required()
      ->check(CLI::PositiveNumber);
  animate_sub->add_option("--dt", dt, "time step")->required()->check(CLI::PositiveNumber);
  animate_sub->add_option("--gravity", gravity, "GX GY GZ")->expected(3);
  animate_sub->add_option("--csv", csv, "write every frame's poses");
  animate_sub->add_option("--svg", svg, "write an animated SVG");
  animate_sub->add_flag("--stop-on-violation", stop,
                        "stop when a frame cannot meet the constraints");

  CLI::App* check_sub =
      app.add_subcommand("check", "degrees of freedom, redundant and conflicting constraints");
  add_common(check_sub, c);

  double from = 0, upto = 6.283185307179586;
  int sweep_steps = 360;
  CLI::App* sweep_sub =
      app.add_subcommand("sweep", "turn one body through a range and report where it locks");
  add_common(sweep_sub, c);
  sweep_sub->add_option("--body", body, "the body to turn")->required();
  sweep_sub->add_option("--axis", axis, "axis X Y Z (world, through the body's centre)")
      ->expected(3);
  sweep_sub->add_option("--from", from, "start angle, radians (default 0)");
  sweep_sub->add_option("--to", upto, "end angle, radians (default 2 pi)");
  sweep_sub->add_option("--steps", sweep_steps, "number of steps (default 360)")
      ->check(CLI::PositiveNumber);
  sweep_sub->add_option("--csv", csv, "write every sample");
  sweep_sub->add_option("--plot", plot, "write an SVG plot of every joint's value");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return kBadInput;
  }
  try {
    if (assemble_sub->parsed()) return assemble_cmd(c, write);
    if (drag_sub->parsed()) return drag_cmd(c, body, to, rotation, steps, csv);
    if (animate_sub->parsed()) return animate_cmd(c, duration, dt, gravity, csv, svg, stop);
    if (check_sub->parsed()) return check_cmd(c);
    if (sweep_sub->parsed()) return sweep_cmd(c, body, axis, from, upto, sweep_steps, csv, plot);
  } catch (const CLI::ValidationError& e) {
    std::cerr << "dispcon: error: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "dispcon: error: " << e.what() << "\n";
    return kBadInput;
  }
  return kBadInput;
}
