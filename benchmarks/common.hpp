// Helpers shared by the benchmark files: loading a sample and timing assembly from fresh copies.
#pragma once

#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/solve/solver.hpp"

namespace bench {

// Times assemble() on a fresh copy of `start` each run; reports the iterations it took.
inline void assemble_copies(benchmark::State& state, const dispcon::Model& start,
                            const dispcon::SolveOptions& o = {}) {
  int iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    dispcon::Model m = start;
    state.ResumeTiming();
    const dispcon::SolveResult r = dispcon::assemble(m, o);
    if (!r.converged) state.SkipWithError(r.message.c_str());
    iterations = r.iterations;
    benchmark::DoNotOptimize(m);
  }
  state.counters["iterations"] = iterations;
}

// A file of samples/, loaded as written (the rough poses); aborts when it does not load.
inline dispcon::Model sample(const std::string& name) {
  dispcon::ParseResult r = dispcon::load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/" + name);
  if (!r.ok()) {
    std::fprintf(stderr, "%s", r.messages().c_str());
    std::abort();
  }
  return std::move(*r.model);
}

}  // namespace bench
