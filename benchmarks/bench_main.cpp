// dispcon against SolveSpace's solver in the same run. scripts/bench runs this and prints the
// ratios; each benchmark reports the iterations it took as a counter.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "common.hpp"
#include "dispcon/solve/diagnostics.hpp"
#include "dispcon/solve/solver.hpp"
#include "mechanisms.hpp"
#include "slvs_include.hpp"

namespace {

using namespace dispcon;
using bench::assemble_copies;

// The numbers of four-bars solved side by side (SolveSpace only up to 400: it takes seconds).
void fourbar_counts(benchmark::internal::Benchmark* b, int up_to) {
  for (int n : {1, 10, 100, 400, 1000}) {
    if (n <= up_to) b->Arg(n);
  }
  b->Unit(benchmark::kMillisecond);
}

// N independent four-bars, the crank fixed, coupler and rocker from a rough start, shared among
// every core (by default a solve takes threads only from 2,500 joints: SolveOptions::threads).
void BM_FourBars_dispcon(benchmark::State& state) {
  SolveOptions o;
  o.threads = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  assemble_copies(state, bench::fourbars_dispcon(static_cast<int>(state.range(0))), o);
}
BENCHMARK(BM_FourBars_dispcon)->Apply([](auto* b) { fourbar_counts(b, 1000); });

// The same on one core (the independent four-bars are otherwise shared among the cores).
void BM_FourBars_dispcon_1core(benchmark::State& state) {
  SolveOptions o;
  o.threads = 1;
  assemble_copies(state, bench::fourbars_dispcon(static_cast<int>(state.range(0))), o);
}
BENCHMARK(BM_FourBars_dispcon_1core)->Apply([](auto* b) { fourbar_counts(b, 1000); });

// SolveSpace on the same four-bars, set up by `solve` (2D sketch or rigid links in 3D).
void solvespace(benchmark::State& state, bench::SlvsResult (*solve)(int)) {
  const int n = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const bench::SlvsResult r = solve(n);
    if (r.result == SLVS_RESULT_TOO_MANY_UNKNOWNS) {
      state.SkipWithError("SolveSpace refuses: too many unknowns");  // rigid: 147 four-bars on
    } else if (r.result != SLVS_RESULT_OKAY) {
      state.SkipWithError("SolveSpace did not solve");
    }
    benchmark::DoNotOptimize(r);
  }
}
void BM_FourBars_slvs(benchmark::State& state) {
  solvespace(state, [](int n) { return bench::fourbars_slvs(n); });
}
BENCHMARK(BM_FourBars_slvs)->Apply([](auto* b) { fourbar_counts(b, 400); }) -> Iterations(3);
// The same sketch with the crank held by an angle constraint (the set-up).
void BM_FourBars_slvs_angle(benchmark::State& state) {
  solvespace(state, [](int n) { return bench::fourbars_slvs(n, {}, true); });
}
BENCHMARK(BM_FourBars_slvs_angle)->Apply([](auto* b) { fourbar_counts(b, 400); }) -> Iterations(3);
// The same set-up on four-bars each of its own size, crank angle and rough start
// (bench::fourbar_variants): the peer of BM_Command_AssembleJson_FourBarsVaried.
void BM_FourBars_slvs_angle_varied(benchmark::State& state) {
  solvespace(state, [](int n) { return bench::fourbars_slvs(bench::fourbar_variants(n), true); });
}
BENCHMARK(BM_FourBars_slvs_angle_varied)->Arg(400)->Unit(benchmark::kMillisecond)->Iterations(3);
void BM_FourBars_slvs_rigid(benchmark::State& state) {
  solvespace(state, [](int n) { return bench::fourbars_slvs_rigid(n); });
}
BENCHMARK(BM_FourBars_slvs_rigid)->Apply([](auto* b) { fourbar_counts(b, 400); }) -> Iterations(3);

// `dispcon check` (assembly, DOF, per-body DOF, redundant joints) of N independent four-bars,
// ranked group by group. Refuses to time an answer other than N times that of one four-bar.
void BM_Check_FourBars(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Model m = bench::fourbars_dispcon(n);
  const CheckResult one = check(bench::fourbars_dispcon(1));
  for (auto _ : state) {
    const CheckResult c = check(m);
    if (!c.solve.converged || c.dof != n * one.dof ||
        c.redundant.size() != static_cast<size_t>(n) * one.redundant.size()) {
      state.SkipWithError("check's answer is not n times that of one four-bar");
    }
    benchmark::DoNotOptimize(c);
  }
  state.counters["redundant"] = static_cast<double>(n * one.redundant.size());
}
BENCHMARK(BM_Check_FourBars)->Arg(25)->Arg(100)->Arg(1000)->Unit(benchmark::kMillisecond);

// `dispcon check` of one large group: the grid of coupled four-bars (n x n cells; 7: 105 links),
// whose Jacobian is one dense block for the rank, the nullspace and the redundant joints. Refuses
// to time a run whose answer is not the first run's (the answers themselves are tested in
// tests/cpp/solve/diagnostics_test.cpp).
void BM_Check_FourBarGrid(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Model m = bench::fourbar_grid(n, n);
  const CheckResult first = check(m);
  if (!first.solve.converged) state.SkipWithError("the grid does not assemble");
  for (auto _ : state) {
    const CheckResult c = check(m);
    if (c.dof != first.dof || c.redundant.size() != first.redundant.size()) {
      state.SkipWithError("check's answer changed from run to run");
    }
    benchmark::DoNotOptimize(c);
  }
  state.counters["bodies"] = m.body_count() - 1;
  state.counters["dof"] = first.dof;
  state.counters["redundant"] = static_cast<double>(first.redundant.size());
}
BENCHMARK(BM_Check_FourBarGrid)->Arg(7)->Unit(benchmark::kMillisecond);

// A closed chain of n point-to-point links, one fixed, from a perturbed circle.
void BM_ClosedChain(benchmark::State& state) {
  assemble_copies(state, bench::closed_chain(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_ClosedChain)->Arg(10)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

// The same at 100,000 links (issue 14: under a second), on one core, timed twice only: a run
// takes about a second. Its own name, so `--benchmark_filter=BM_ClosedChain_Large` runs it alone
// and `--benchmark_filter=-BM_ClosedChain_Large` leaves it out.
void BM_ClosedChain_Large(benchmark::State& state) {
  SolveOptions o;
  o.threads = 1;
  assemble_copies(state, bench::closed_chain(static_cast<int>(state.range(0))), o);
}
BENCHMARK(BM_ClosedChain_Large)->Arg(100000)->Iterations(2)->Unit(benchmark::kMillisecond);

// One drag step of a link of a closed chain of n links (a live drag's frame).
void BM_DragStep_ClosedChain(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Model m = bench::closed_chain(n);
  assemble(m);
  const BodyId b{n / 2};
  const Pose p0 = m.body(b).pose;
  Dragger drag(m, b);
  int k = 0, iterations = 0;
  for (auto _ : state) {
    Pose t = p0;
    t.x.z() += 0.002 * std::sin(0.01 * k++);  // up and down, small steps
    const SolveResult r = drag.move_to(t);
    if (!r.converged) state.SkipWithError(r.message.c_str());
    iterations = r.iterations;
  }
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_DragStep_ClosedChain)->Arg(20)->Arg(100)->Arg(400)->Unit(benchmark::kMicrosecond);

// A grid of coupled four-bars: rows x cols cells of pinned links (many closed loops).
void BM_FourBarGrid(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Model start = bench::fourbar_grid(n, n);
  assemble_copies(state, start);
  state.counters["bodies"] = start.body_count() - 1;
}
BENCHMARK(BM_FourBarGrid)->Arg(3)->Arg(10)->Arg(20)->Unit(benchmark::kMillisecond);

// One drag step of a grid of coupled four-bars (rows = cols = n): the first link, a vertical of
// the bottom row pinned to the ground at its origin, is turned about its pin a little each frame
// and every loop shears to follow. (Pushing a top link sideways while holding its height asks
// for the impossible: the columns are straight, so any shear lowers the top row.)
void BM_DragStep_FourBarGrid(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Model m = bench::fourbar_grid(n, n);
  if (!assemble(m).converged) state.SkipWithError("the grid does not assemble");
  const BodyId b{1};
  const Pose p0 = m.body(b).pose;
  Dragger drag(m, b);
  int k = 0, iterations = 0;
  for (auto _ : state) {
    Pose t = p0;
    t.q = quat_from_rotation_vector(Vec3(0, 0, 0.2 * std::sin(0.01 * k++))) * p0.q;
    const SolveResult r = drag.move_to(t);
    if (!r.converged) state.SkipWithError(r.message.c_str());
    iterations = std::max(iterations, r.iterations);
  }
  state.counters["iterations"] = iterations;
  state.counters["bodies"] = m.body_count() - 1;
}
BENCHMARK(BM_DragStep_FourBarGrid)->Arg(3)->Arg(7)->Arg(10)->Unit(benchmark::kMicrosecond);

// One drag step of a train of n gears (issue 11): the first gear turned 0.01 rad further each
// frame, every other gear following through its mesh; the last gear's turn is checked against
// the ratio (r_0 / r_(n-1)) at the end.
void BM_DragStep_GearTrain(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Model m = bench::gear_train(n);
  Dragger drag(m, BodyId{1});
  int k = 0, iterations = 0;
  for (auto _ : state) {
    const SolveResult r = drag.move_to(Pose::from(Vec3::Zero(), Vec3(0, 0, 0.01 * ++k)));
    if (!r.converged) state.SkipWithError(r.message.c_str());
    iterations = std::max(iterations, r.iterations);
  }
  // The last gear turns (-1)^(n-1) r_0 / r_(n-1) times the first, to within what the meshes'
  // tolerance lets add up along the train (each ratio is 2 or 1/2: at most 2 n tolerances).
  const double expected = (n % 2 ? 1 : -2) * 0.01 * k;
  const Vec3 e = m.body(BodyId{n}).pose.q * Vec3::UnitX();
  const double error = std::abs(std::remainder(std::atan2(e.y(), e.x()) - expected, 2 * M_PI));
  state.counters["ratio_error"] = error;
  if (error > 2 * n * SolveOptions{}.tolerance) {
    state.SkipWithError("the last gear is off its ratio");
  }
  state.counters["iterations"] = iterations;
  state.counters["bodies"] = n;
}
BENCHMARK(BM_DragStep_GearTrain)->Arg(10)->Arg(100)->Unit(benchmark::kMicrosecond);

// Both solvers must agree on the four-bars before their times are compared: the copies of one
// four-bar, and four-bars each of its own (fourbar_variants, the varied file's).
bool same_answer() {
  for (const bool varied : {false, true}) {
    for (int n : {1, 10, 100}) {
      if (!varied && n > 10) continue;
      const std::vector<bench::FourBarProblem> problems =
          varied ? bench::fourbar_variants(n) : bench::fourbar_copies(n);
      Model m = bench::fourbars_dispcon(problems);
      SolveOptions o;
      o.tolerance = 1e-12;
      if (!assemble(m, o).converged) return false;
      for (const char* setup : {"2D", "2D angle", "rigid"}) {
        const bench::SlvsResult s = setup[0] == 'r'   ? bench::fourbars_slvs_rigid(problems)
                                    : setup[2] == 'a' ? bench::fourbars_slvs(problems, true)
                                                      : bench::fourbars_slvs(problems);
        if (s.result != SLVS_RESULT_OKAY) {
          std::fprintf(stderr, "SolveSpace (%s%s) failed: result %d\n", setup,
                       varied ? ", varied" : "", s.result);
          return false;
        }
        for (int k = 0; k < n; ++k) {
          const double diff = std::abs(std::remainder(
              bench::rocker_angle_dispcon(m, k) - s.rocker[static_cast<size_t>(k)], 2 * M_PI));
          if (diff > 1e-8) {
            std::fprintf(stderr, "four-bar %d%s: dispcon and SolveSpace (%s) differ by %g rad\n", k,
                         varied ? " (varied)" : "", setup, diff);
            return false;
          }
        }
      }
    }
  }
  std::fprintf(
      stderr,
      "check: dispcon and SolveSpace (2D, 2D angle and rigid) give the same rocker angles (within "
      "1e-8 rad), on copies of one four-bar and on 100 four-bars each of its own\n");
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (!same_answer()) return 1;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
