// `dispcon animate`: the physics variant (seed section 2.2): integrate, re-establish the
// constraints, then correct the speeds.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "dispcon/io/svg.hpp"
#include "dispcon/solve/dynamics.hpp"
#include "report.hpp"

namespace dispcon::cli {
namespace {

struct AnimateArgs {
  Common common;
  double duration = 1, dt = 0.01;
  std::vector<double> gravity;
  std::string csv, svg;
  bool stop = false;
};

int run_animate(const AnimateArgs& a) {
  auto m = load(a.common.file);
  if (!m) return kBadInput;
  AnimateOptions o;
  o.duration = a.duration;
  o.dt = a.dt;
  if (!a.gravity.empty()) o.gravity = vec(a.gravity);
  o.stop_on_violation = a.stop;
  o.solve = options(a.common);
  const AnimateResult r = animate(*m, o);
  if (!a.csv.empty()) {
    std::ofstream out(a.csv);
    out << "time,body,px,py,pz,qw,qx,qy,qz\n";
    char t[64];
    for (const Frame& f : r.frames) {
      std::snprintf(t, sizeof t, "%.9g", f.time);
      csv_rows(out, t, *m, f.poses);
    }
    if (!written(out, a.csv)) return kBadInput;
  }
  if (!a.svg.empty() && !write_text(a.svg, write_animation_svg(*m, r))) return kBadInput;
  const std::vector<ConstraintReport> now = measure(*m, m->poses(), o.solve);
  if (a.common.json) {
    auto frames = [&](JsonWriter& w) {
      w.begin_array();
      for (const Frame& f : r.frames) {
        write_object(w, {{"time", [&](JsonWriter& v) { v.value(f.time); }},
                         {"iterations", [&](JsonWriter& v) { v.value(f.iterations); }},
                         {"max_residual", [&](JsonWriter& v) { v.value(f.max_residual); }},
                         {"converged", [&](JsonWriter& v) { v.value(f.converged); }},
                         {"violated", [&](JsonWriter& v) { write_joint_list(v, f.violated); }}});
      }
      w.end_array();
    };
    const std::vector<Pose> poses = m->poses();
    print_json([&](JsonWriter& w) {
      write_object(w, {{"converged", [&](JsonWriter& v) { v.value(r.converged); }},
                       {"stopped", [&](JsonWriter& v) { v.value(r.stopped); }},
                       {"iterations", [&](JsonWriter& v) { v.value(r.iterations); }},
                       {"max_residual", [&](JsonWriter& v) { v.value(r.max_residual); }},
                       {"message", [&](JsonWriter& v) { v.value(r.message); }},
                       {"warnings", [&](JsonWriter& v) { write_strings(v, r.warnings); }},
                       {"bodies", [&](JsonWriter& v) { write_bodies(v, *m, poses); }},
                       {"constraints", [&](JsonWriter& v) { write_constraints(v, *m, now); }},
                       {"frames", frames}});
    });
  } else {
    std::cout << a.common.file << ": " << r.message << "\n";
    for (const std::string& w : r.warnings)
      std::cerr << a.common.file << ": warning: " << w << "\n";
    print_poses(std::cout, *m, m->poses());
  }
  return r.converged ? kOk : kViolated;
}

}  // namespace

Subcommand add_animate(CLI::App& app) {
  auto args = std::make_shared<AnimateArgs>();
  CLI::App* sub =
      app.add_subcommand("animate", "the physics variant: integrate, constrain, correct speeds");
  add_common(sub, args->common);
  // Checked by the engine (validate(AnimateOptions)), as every number is.
  sub->add_option("--duration", args->duration, "seconds")->required();
  sub->add_option("--dt", args->dt, "time step")->required();
  sub->add_option("--gravity", args->gravity, "GX GY GZ")->expected(3);
  sub->add_option("--csv", args->csv, "write every frame's poses");
  sub->add_option("--svg", args->svg, "write an animated SVG");
  sub->add_flag("--stop-on-violation", args->stop, "stop when a frame cannot meet the constraints");
  return {sub, [args] { return run_animate(*args); }};
}

}  // namespace dispcon::cli
