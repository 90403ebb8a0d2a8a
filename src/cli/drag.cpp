// `dispcon drag`: one body held on a path while the rest of the mechanism follows, each step
// starting from the previous one's result (continuity, seed section 2.3).
#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "report.hpp"

namespace dispcon::cli {
namespace {

struct DragArgs {
  Common common;
  std::string body, csv;
  std::vector<double> to, rotation;
  int steps = 50;
};

int run_drag(const DragArgs& a) {
  auto m = load(a.common.file);
  if (!m) return kBadInput;
  const BodyId body = body_named(*m, a.body);
  const SolveOptions o = options(a.common);
  const SolveResult first = assemble(*m, o);
  Pose target = m->body(body).pose;
  target.x = vec(a.to);  // checked by the engine's drag, as the rotation vector is here
  if (!a.rotation.empty()) target.q = rotation_from_vector(vec(a.rotation), "--rotation");
  std::vector<std::vector<Pose>> poses;
  DragResult d;
  if (first.converged) {
    d = drag(*m, body, target, a.steps, o, &poses);
  } else {
    d.converged = false;
    d.failed_step = 0;
    d.message = "the model does not assemble: " + first.message;
  }
  if (!a.csv.empty()) {
    std::ofstream out(a.csv);
    out << "step,body,px,py,pz,qw,qx,qy,qz\n";
    for (size_t k = 0; k < poses.size(); ++k) csv_rows(out, std::to_string(k + 1), *m, poses[k]);
    if (!written(out, a.csv)) return kBadInput;
  }
  const bool converged = d.converged && first.converged;
  const std::vector<ConstraintReport> now =
      d.steps.empty() ? first.constraints : d.steps.back().constraints;
  if (a.common.json) {
    auto steps = [&](JsonWriter& w) {
      w.begin_array();
      for (const SolveResult& s : d.steps) {
        if (s.status != SolveStatus::OutOfReach) {
          write_object(w, {{"iterations", [&](JsonWriter& v) { v.value(s.iterations); }},
                           {"max_residual", [&](JsonWriter& v) { v.value(s.max_residual); }},
                           {"converged", [&](JsonWriter& v) { v.value(s.converged); }}});
          continue;
        }
        // An extension of cli.md's step: the body held out of reach and the distance left (and
        // the angle left, when the rotation is what is out of reach).
        auto reach = [&](JsonWriter& v) {
          std::vector<Member> members = {
              {"body", [&](JsonWriter& b) { b.value(m->body(s.held).name); }},
              {"distance_left", [&](JsonWriter& b) { b.value(s.distance_left); }}};
          if (s.angle_left > 0) {
            members.push_back({"angle_left", [&](JsonWriter& b) { b.value(s.angle_left); }});
          }
          write_object(v, std::move(members));
        };
        write_object(w, {{"iterations", [&](JsonWriter& v) { v.value(s.iterations); }},
                         {"max_residual", [&](JsonWriter& v) { v.value(s.max_residual); }},
                         {"converged", [&](JsonWriter& v) { v.value(s.converged); }},
                         {"out_of_reach", reach}});
      }
      w.end_array();
    };
    const std::vector<Pose> poses = m->poses();
    print_json([&](JsonWriter& w) {
      write_object(
          w, {{"converged", [&](JsonWriter& v) { v.value(converged); }},
              {"iterations", [&](JsonWriter& v) { v.value(first.iterations + d.iterations); }},
              {"max_residual",
               [&](JsonWriter& v) { v.value(std::max(first.max_residual, d.max_residual)); }},
              {"message", [&](JsonWriter& v) { v.value(d.message); }},
              {"failed_step", [&](JsonWriter& v) { v.value(d.failed_step); }},
              {"bodies", [&](JsonWriter& v) { write_bodies(v, *m, poses); }},
              {"constraints", [&](JsonWriter& v) { write_constraints(v, *m, now); }},
              {"steps", steps}});
    });
  } else {
    std::cout << a.common.file << ": assembled: " << first.message << "\n" << d.message << "\n";
    if (!d.steps.empty()) {
      int worst = 0;
      for (const SolveResult& s : d.steps) worst = std::max(worst, s.iterations);
      std::cout << "iterations per step: mean " << d.iterations * 1.0 / d.steps.size() << ", worst "
                << worst << "\n";
    }
    print_poses(std::cout, *m, m->poses());
  }
  return converged ? kOk : kViolated;
}

}  // namespace

Subcommand add_drag(CLI::App& app) {
  auto args = std::make_shared<DragArgs>();
  CLI::App* sub = app.add_subcommand("drag", "hold one body on a path while the rest follows");
  add_common(sub, args->common);
  sub->add_option("--body", args->body, "the body to move")->required();
  sub->add_option("--to", args->to, "target position X Y Z")->required()->expected(3);
  sub->add_option("--rotation", args->rotation, "target rotation vector RX RY RZ")->expected(3);
  sub->add_option("--steps", args->steps, "number of equal steps (default 50)");
  sub->add_option("--csv", args->csv, "write every step's poses");
  return {sub, [args] { return run_drag(*args); }};
}

}  // namespace dispcon::cli
