// Reading, writing and the whole command (issue 14): the .dcl of N four-bars as dispcon writes it
// (the rough start of BM_FourBars_dispcon, 17 significant digits a number), read by load_dcl;
// the JSON document of their assembly, written; and
// `dispcon assemble FILE --json` run as a process, timed from posix_spawn to exit, its CPU time
// (user and system, from wait4) reported beside.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <string>

#include "common.hpp"
#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/io/dcl_writer.hpp"
#include "mechanisms.hpp"
#include "report.hpp"

namespace {

using namespace dispcon;

// Written once per size, beside the benchmark binary's build (scripts/bench names it).
std::string fourbars_file(int n) {
  const std::string path =
      std::string(DISPCON_BUILD_DIR) + "/fourbars-" + std::to_string(n) + ".dcl";
  std::ofstream(path, std::ios::binary) << write_dcl(bench::fourbars_dispcon(n));
  return path;
}

void BM_Load_FourBars(benchmark::State& state) {
  const std::string path = fourbars_file(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    const ParseResult r = load_dcl(path);
    if (!r.ok()) state.SkipWithError(r.messages().c_str());
    benchmark::DoNotOptimize(r);
  }
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(in.tellg()));
}
BENCHMARK(BM_Load_FourBars)->Arg(400)->Unit(benchmark::kMillisecond);

// The JSON document `dispcon assemble --json` prints for the N four-bars once assembled, written
// by the command's own code (report.cpp, json_writer.cpp) into a string, as print_json holds its
// last piece before it goes out.
void BM_Json_FourBars(benchmark::State& state) {
  Model model = bench::fourbars_dispcon(static_cast<int>(state.range(0)));
  const SolveResult r = assemble(model);
  if (!r.converged) state.SkipWithError("the four-bars did not assemble");
  size_t bytes = 0;
  for (auto _ : state) {
    std::string out;
    {
      cli::JsonWriter w(out);
      cli::write_object(w, cli::solve_members(model, r));
    }
    bytes = out.size();
    benchmark::DoNotOptimize(out);
  }
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(bytes));
}
BENCHMARK(BM_Json_FourBars)->Arg(400)->Unit(benchmark::kMillisecond);

#ifdef DISPCON_BIN
// The whole `dispcon assemble FILE --json` (its output to /dev/null), as a user waits for it.
void BM_Command_AssembleJson_FourBars(benchmark::State& state) {
  const std::string path = fourbars_file(static_cast<int>(state.range(0)));
  double cpu = 0;
  // posix_spawn, not fork: a fork of this benchmark process (hundreds of MB mapped by the
  // benchmarks before it) copied its page tables, and the child's CPU time counted their teardown:
  // 59 ms of CPU measured for a process that takes 34 ms alone (perf stat).
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  std::string bin = DISPCON_BIN, sub = "assemble", flag = "--json", file = path;
  char* argv[] = {bin.data(), sub.data(), file.data(), flag.data(), nullptr};
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    pid_t pid = 0;
    if (posix_spawn(&pid, DISPCON_BIN, &actions, nullptr, argv, environ) != 0) {
      state.SkipWithError("dispcon could not be started");
      break;
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(wall.count());
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) state.SkipWithError("dispcon failed");
    cpu += usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
           1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  }
  posix_spawn_file_actions_destroy(&actions);
  state.counters["cpu_ms"] = 1e3 * cpu / static_cast<double>(state.iterations());
}
BENCHMARK(BM_Command_AssembleJson_FourBars)
    ->Arg(400)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
#endif

}  // namespace
