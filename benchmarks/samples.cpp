// Assembly and dragging of the samples in samples/, one benchmark of each per sample:
//   BM_Sample_Assemble/<name>  assemble() from the file's rough poses; counter: its iterations.
//   BM_Sample_DragStep/<name>  after assembly, one step of a live drag: the sample's input body
//                              turned by a small step about its joint's axis while the rest
//                              follows; counter: the mean iterations per step.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "common.hpp"
#include "dispcon/solve/solver.hpp"

namespace {

using namespace dispcon;

struct SampleCase {
  const char* name;  // samples/<name>.dcl, and the benchmarks' suffix
  // The body a person would drag (its joint gives the axis and the pivot); nullptr: no drag.
  const char* input;
  // 0: the input turns on and on, 0.01 rad per step. Otherwise it cannot go round (a lock-up, a
  // limit, a fold): angle = amplitude * sin(0.01 k) from the assembled pose, so every step stays
  // within reach and no longer than 0.01 rad.
  double amplitude;
};

// Left out: conflicting.dcl (meant to fail), snake.dcl (physics only; it starts on its joints, so
// assembly does nothing, and nothing in it is an input to turn) and monocycle-push.dcl (the
// monocycle with masses and a force, for `dispcon animate`; monocycle.dcl covers the mechanism).
constexpr SampleCase kSamples[] = {
    // The crank of a crank-rocker (Grashof) turns fully.
    {"fourbar", "crank", 0},
    // The engine's crank turns fully (r + e = 1.2 < l = 3).
    {"slider-crank", "crank", 0},
    // Bennett: the first moving link turns fully about its revolute with the world.
    {"bennett", "link2", 0},
    // Sarrus: a limb's first link drives the platform; it goes round (the platform runs up and
    // down, the limbs passing their straight positions, where the drag still converges).
    {"sarrus", "a1", 0},
    // Peaucellier: the crank locks at +-2.32 rad where the arms straighten; assembled at 1.0,
    // it swings by +-1 rad.
    {"peaucellier", "crank", 1.0},
    // The arm's base, about the vertical; its twist limit is +-2.5 rad, it swings +-1 rad.
    {"robot-arm", "base", 1.0},
    // Bricard 6R: the first moving link does not go round; it locks 1.09 rad one way and 3.10
    // rad the other from the assembled pose (a range of 4 pi / 3, `dispcon sweep` finds both).
    // It swings by +-0.8 rad.
    {"bricard", "link2", 0.8},
    // The input rocker locks at 0.64 and 1.52 rad; assembled at 1.01, it swings by +-0.3 rad.
    {"double-rocker", "input", 0.3},
    // 0 degrees of freedom: nothing to drag.
    {"welded", nullptr, 0},
    // The otary's head nods about its z (the axis of the file's torque); the twist limits of the
    // neck and the hip stop it 0.87 rad one way and 1.33 rad the other. It swings by +-0.5 rad.
    {"otary", "head", 0.5},
    // The monocycle pedalled: the wheel turns fully about its axle (the paper's demonstration).
    {"monocycle", "wheel", 0},
    // Couplings (issue 11). The first gear of the train turns on and on.
    {"three-gears", "g1", 0},
    // The sun of the planetary set turns on and on (the ring and carrier share the other
    // freedom as the solver finds them).
    {"planetary", "sun", 0},
    // The steering pinion swings +-0.6 rad (the rack +-0.18; the tie rods are far from toggle).
    {"steering", "pinion", 0.6},
    // The vice's input is the jaw's travel, not a turn: assembled only.
    {"vice", nullptr, 0},
};

Model load(const SampleCase& c) {
  return bench::sample(std::string(c.name) + ".dcl");
}

void assemble_sample(benchmark::State& state, const SampleCase& c) {
  bench::assemble_copies(state, load(c));
}

// The axis and the pivot, in the body's frame, of the first joint that turns `body` about an
// axis: a hinge with an angle part (a revolute, or a ball with a cone).
struct Turn {
  Vec3 axis;
  Vec3 pivot;
};

Turn turn_of(const Model& m, BodyId body) {
  for (const Joint& j : m.joints()) {
    if (!j.has_hinge || !j.angle) continue;
    if (j.body2 == body) return {j.angle->a2.normalized(), j.p2};
    if (j.body1 == body) return {j.angle->a1.normalized(), j.p1};
  }
  std::fprintf(stderr, "%s: no hinge with an angle part to turn it about\n",
               m.body(body).name.c_str());
  std::abort();
}

void drag_sample(benchmark::State& state, const SampleCase& c) {
  Model m = load(c);
  const SolveResult a = assemble(m);
  if (!a.converged) {
    state.SkipWithError(a.message.c_str());
    return;
  }
  const BodyId body = *m.find(c.input);
  const Pose p0 = m.body(body).pose;
  const Turn t = turn_of(m, body);
  const Vec3 axis = p0.q * t.axis;
  const Vec3 pivot = p0.apply(t.pivot);
  Dragger drag(m, body);
  int k = 0;
  double iterations = 0, steps = 0;
  for (auto _ : state) {
    ++k;
    const double angle = c.amplitude > 0 ? c.amplitude * std::sin(0.01 * k) : 0.01 * k;
    const Quat turn = quat_from_rotation_vector(axis * angle);
    Pose p;
    p.q = turn * p0.q;
    p.x = pivot + turn * (p0.x - pivot);
    const SolveResult r = drag.move_to(p);
    if (!r.converged) {
      state.SkipWithError(("step " + std::to_string(k) + ": " + r.message).c_str());
      break;
    }
    iterations += r.iterations;
    ++steps;
  }
  state.counters["iterations"] = iterations / std::max(1.0, steps);
}

[[maybe_unused]] const bool registered = [] {
  for (const SampleCase& c : kSamples) {
    const std::string name = std::string("BM_Sample_Assemble/") + c.name;
    benchmark::RegisterBenchmark(name.c_str(), assemble_sample, c)->Unit(benchmark::kMicrosecond);
  }
  for (const SampleCase& c : kSamples) {
    if (!c.input) continue;
    const std::string name = std::string("BM_Sample_DragStep/") + c.name;
    benchmark::RegisterBenchmark(name.c_str(), drag_sample, c)->Unit(benchmark::kMicrosecond);
  }
  return true;
}();

}  // namespace
