// `dispcon sweep`: the range of motion of one body turned about an axis, and where it locks.
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "dispcon/io/sweep_plot.hpp"
#include "dispcon/solve/diagnostics.hpp"
#include "report.hpp"

namespace dispcon::cli {
namespace {

struct SweepArgs {
  Common common;
  std::string body, csv, plot;
  std::vector<double> axis = {0, 0, 1};
  double from = 0, to = 2 * kPi;
  int steps = 360;
};

int run_sweep(const SweepArgs& a) {
  auto m = load(a.common.file);
  if (!m) return kBadInput;
  SweepOptions s;
  s.body = body_named(*m, a.body);
  s.axis = vec(a.axis);
  s.from = a.from;
  s.to = a.to;
  s.steps = a.steps;
  s.solve = options(a.common);
  const SweepResult r = sweep(*m, s);
  if (!a.csv.empty()) {
    std::ofstream out(a.csv);
    out << "value,converged,max_residual";
    for (int j = 0; j < m->joint_count(); ++j) out << ",joint" << j;
    out << "\n";
    for (const SweepSample& x : r.samples) {
      out << x.value << "," << (x.converged ? 1 : 0) << "," << x.max_residual;
      for (double v : x.joint_values) out << "," << v;
      out << "\n";
    }
    if (!written(out, a.csv)) return kBadInput;
  }
  if (!a.plot.empty() && !write_text(a.plot, write_sweep_svg(*m, r))) return kBadInput;
  if (a.common.json) {
    auto samples = [&](JsonWriter& w) {
      w.begin_array();
      for (const SweepSample& x : r.samples) {
        write_object(
            w, {{"value", [&](JsonWriter& v) { v.value(x.value); }},
                {"converged", [&](JsonWriter& v) { v.value(x.converged); }},
                {"max_residual", [&](JsonWriter& v) { v.value(x.max_residual); }},
                {"limits_active", [&](JsonWriter& v) { write_joint_list(v, x.limits_active); }},
                {"joint_values", [&](JsonWriter& v) {
                   v.begin_array();
                   for (const double j : x.joint_values) v.value(j);
                   v.end_array();
                 }}});
      }
      w.end_array();
    };
    print_json([&](JsonWriter& w) {
      write_object(w, {{"converged", [&](JsonWriter& v) { v.value(!r.locked); }},
                       {"locked", [&](JsonWriter& v) { v.value(r.locked); }},
                       {"lock_value", [&](JsonWriter& v) { v.value(r.lock_value); }},
                       {"message", [&](JsonWriter& v) { v.value(r.message); }},
                       {"samples", samples}});
    });
  } else {
    std::cout << a.common.file << ": " << r.message << "\n";
  }
  return r.locked ? kViolated : kOk;
}

}  // namespace

Subcommand add_sweep(CLI::App& app) {
  auto args = std::make_shared<SweepArgs>();
  CLI::App* sub =
      app.add_subcommand("sweep", "turn one body through a range and report where it locks");
  add_common(sub, args->common);
  sub->add_option("--body", args->body, "the body to turn")->required();
  sub->add_option("--axis", args->axis, "axis X Y Z (world, through the body's centre)")
      ->expected(3);
  sub->add_option("--from", args->from, "start angle, radians (default 0)");
  sub->add_option("--to", args->to, "end angle, radians (default 2 pi)");
  sub->add_option("--steps", args->steps, "number of steps (default 360)");
  sub->add_option("--csv", args->csv, "write every sample");
  sub->add_option("--plot", args->plot, "write an SVG plot of every joint's value");
  return {sub, [args] { return run_sweep(*args); }};
}

}  // namespace dispcon::cli
