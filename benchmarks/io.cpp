// Reading, writing and the whole command (issue 14): the .dcl of N four-bars as dispcon writes it
// (the rough start of BM_FourBars_dispcon, 17 significant digits a number), read by load_dcl;
// the JSON document of their assembly, written; and
// `dispcon assemble FILE --json` run as a process, timed from posix_spawn to exit, its CPU time
// (user and system, from wait4) reported beside, and the floor of any process spawned the same way.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "common.hpp"
#include "dispcon/io/dcl_lexer.hpp"
#include "dispcon/io/dcl_parser.hpp"
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
// The same of four-bars each of its own size, crank angle and rough start
// (bench::fourbar_variants): no number of the file nor of the document repeats from one four-bar
// to the next.
std::string fourbars_varied_file(int n) {
  const std::string path =
      std::string(DISPCON_BUILD_DIR) + "/fourbars-varied-" + std::to_string(n) + ".dcl";
  std::ofstream(path, std::ios::binary)
      << write_dcl(bench::fourbars_dispcon(bench::fourbar_variants(n)));
  return path;
}

// The page faults a read takes are counted too: on this VM a page touched for the first time
// costs 12-20 us, more than the read of a hundred lines, and how many a read meets depends on
// whether malloc kept the previous read's pages (its trim and mmap thresholds follow the blocks
// freed before, by this benchmark or others in the same process).
long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

void BM_Load_FourBars(benchmark::State& state) {
  const std::string path = fourbars_file(static_cast<int>(state.range(0)));
  const long faults = minor_faults();
  for (auto _ : state) {
    const ParseResult r = load_dcl(path);
    if (!r.ok()) state.SkipWithError(r.messages().c_str());
    benchmark::DoNotOptimize(r);
  }
  state.counters["faults"] = benchmark::Counter(static_cast<double>(minor_faults() - faults),
                                                benchmark::Counter::kAvgIterations);
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(in.tellg()));
}
BENCHMARK(BM_Load_FourBars)->Arg(400)->Unit(benchmark::kMillisecond);

// The floors under BM_Load_FourBars, each one step of the read alone, on the same file: `read`,
// the file into memory (read_file: open, size, one read, close); `scan`, that and one pass over
// its every byte (its new lines counted), what any reader of the text costs at the least;
// `lex`, that and every token by DclLexer, what the parse and the model build on. The rest of
// BM_Load_FourBars is the parser's and the model's.
enum class ReadStep { Read, Scan, Lex };
void BM_Load_FourBars_Floor(benchmark::State& state, ReadStep step) {
  const std::string path = fourbars_file(static_cast<int>(state.range(0)));
  size_t count = 0;
  for (auto _ : state) {
    dcl::FileText file;
    std::string why;
    if (!dcl::read_file(path, file, why)) {
      state.SkipWithError(why.c_str());
      break;
    }
    const std::string_view text = file.view();
    count = 0;
    if (step == ReadStep::Scan) {
      count = static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
    } else if (step == ReadStep::Lex) {
      LexErrors errors;
      DclLexer lexer(text, errors);
      Token t;
      do {
        lexer.next(t);
        ++count;
      } while (t.kind != Token::End);
      if (!errors.listed.empty()) state.SkipWithError(errors.listed.front().message.c_str());
    }
    benchmark::DoNotOptimize(count);
    benchmark::DoNotOptimize(text);
  }
  state.counters["count"] = static_cast<double>(count);  // lines or tokens
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(in.tellg()));
}
BENCHMARK_CAPTURE(BM_Load_FourBars_Floor, read, ReadStep::Read)
    ->Arg(400)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Load_FourBars_Floor, scan, ReadStep::Scan)
    ->Arg(400)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Load_FourBars_Floor, lex, ReadStep::Lex)
    ->Arg(400)
    ->Unit(benchmark::kMillisecond);

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

// The median of a sample (sorted in place).
double median(std::vector<double>& v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

// A program run as a process, as a user waits for it (its output to /dev/null): wall time from
// posix_spawn to the exit reaped by wait4 (the benchmark's time), and the child's CPU time (user
// and system, from wait4's rusage). The counters `cpu_ms` and `wall_ms` are the medians of the
// runs, what a typical run costs: on the shared development VM a few runs of a repetition take
// several milliseconds more, and the mean (`cpu_mean_ms`) follows them (2 ms above the median in
// a repetition of 20 runs, docs/performance.md). `user_ms`, `sys_ms` and `faults` are means. The
// parent's size does not change what the child costs: spawned alternately from a process holding
// 800 MB and from a small one, the same CPU time.
void time_process(benchmark::State& state, const std::string& bin, std::vector<std::string> args) {
  std::vector<double> cpu, wall;
  double user = 0, sys = 0, faults = 0;
  // posix_spawn, not fork: a fork of this benchmark process (hundreds of MB mapped by the
  // benchmarks before it) copied its page tables, and the child's CPU time counted their teardown:
  // 59 ms of CPU measured for a process that takes 34 ms alone (perf stat).
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  args.insert(args.begin(), bin);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    pid_t pid = 0;
    if (posix_spawn(&pid, bin.c_str(), &actions, nullptr, argv.data(), environ) != 0) {
      state.SkipWithError((bin + " could not be started").c_str());
      break;
    }
    int status = 0;
    rusage usage{};
    wait4(pid, &status, 0, &usage);
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    state.SetIterationTime(elapsed.count());
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      state.SkipWithError((bin + " failed").c_str());
      break;
    }
    const double u = static_cast<double>(usage.ru_utime.tv_sec) + 1e-6 * usage.ru_utime.tv_usec;
    const double k = static_cast<double>(usage.ru_stime.tv_sec) + 1e-6 * usage.ru_stime.tv_usec;
    user += u;
    sys += k;
    cpu.push_back(u + k);
    wall.push_back(elapsed.count());
    faults += static_cast<double>(usage.ru_minflt + usage.ru_majflt);
  }
  posix_spawn_file_actions_destroy(&actions);
  const double runs = static_cast<double>(std::max<size_t>(1, cpu.size()));
  state.counters["cpu_mean_ms"] = 1e3 * (user + sys) / runs;
  state.counters["cpu_ms"] = 1e3 * median(cpu);
  state.counters["wall_ms"] = 1e3 * median(wall);
  state.counters["user_ms"] = 1e3 * user / runs;
  state.counters["sys_ms"] = 1e3 * sys / runs;
  state.counters["faults"] = faults / runs;
}

// What any process costs on this machine, spawned and timed as the command is below, so that the
// command's figure and the floor under it come from one run: a program with no C library that
// only exits (the kernel's exec and exit: on the development VM most of a millisecond more than
// the same on bare hardware), and an empty program linked as the command is (glibc's start and
// exit added; its `cpuid`s trap to the hypervisor there), and between them the first with the
// 41 `cpuid`s of glibc's start (what they alone cost). benchmarks/floor/.
void BM_Command_Floor(benchmark::State& state, const char* bin) {
  time_process(state, bin, {});
}
#ifdef DISPCON_FLOOR_NO_LIBC
BENCHMARK_CAPTURE(BM_Command_Floor, no_libc, DISPCON_FLOOR_NO_LIBC)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
#endif
#ifdef DISPCON_FLOOR_CPUID
BENCHMARK_CAPTURE(BM_Command_Floor, cpuid, DISPCON_FLOOR_CPUID)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
#endif
#ifdef DISPCON_FLOOR_STATIC_EMPTY
BENCHMARK_CAPTURE(BM_Command_Floor, static_empty, DISPCON_FLOOR_STATIC_EMPTY)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
#endif

#ifdef DISPCON_BIN
// The whole `dispcon assemble FILE --json` of N four-bars. With one four-bar, what the command's
// own start, reading, solving and writing cost beside the floor above.
void BM_Command_AssembleJson_FourBars(benchmark::State& state) {
  time_process(state, DISPCON_BIN,
               {"assemble", fourbars_file(static_cast<int>(state.range(0))), "--json"});
}
BENCHMARK(BM_Command_AssembleJson_FourBars)
    ->Arg(1)
    ->Arg(400)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);
// The same of N four-bars each of its own (fourbars_varied_file): what the 400 copies of one
// four-bar cost without their repeats (the JSON's memo of numbers finds none), against
// BM_FourBars_slvs_angle_varied, SolveSpace's angle set-up of the same linkages.
void BM_Command_AssembleJson_FourBarsVaried(benchmark::State& state) {
  time_process(state, DISPCON_BIN,
               {"assemble", fourbars_varied_file(static_cast<int>(state.range(0))), "--json"});
}
BENCHMARK(BM_Command_AssembleJson_FourBarsVaried)
    ->Arg(400)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// The closed chain of n links (bench::closed_chain, BM_ClosedChain_Large's model) as dispcon
// writes it, once per size beside the benchmark binary's build: 100,000 links are 21 MB of text,
// made here rather than kept in the repository.
std::string closed_chain_file(int n) {
  const std::string path =
      std::string(DISPCON_BUILD_DIR) + "/closed-chain-" + std::to_string(n) + ".dcl";
  std::ofstream(path, std::ios::binary) << write_dcl(bench::closed_chain(n));
  return path;
}

// The whole `dispcon assemble FILE` of the 100,000-link closed chain as a user meets it (issue
// 14: under a second): a process that reads the file, solves once (its first solve: every buffer
// fresh) and prints the poses, in text (Arg 0) or with --json (Arg 1). Twice only: a run takes
// about a second.
void BM_Command_Assemble_ClosedChain(benchmark::State& state) {
  std::vector<std::string> args{"assemble", closed_chain_file(static_cast<int>(state.range(0)))};
  if (state.range(1)) args.push_back("--json");
  time_process(state, DISPCON_BIN, args);
}
BENCHMARK(BM_Command_Assemble_ClosedChain)
    ->Args({100000, 0})
    ->Args({100000, 1})
    ->Iterations(2)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond);

// The same command of other builds, named by DISPCON_BENCH_OTHER (paths separated by ':';
// registered only when set): builds compared in one run, their repetitions alternated with
// --benchmark_enable_random_interleaving=true (the machine's load changes from minute to minute).
// The k-th is BM_Command_AssembleJson_FourBars_Other<k>, of the varied file
// BM_Command_AssembleJson_FourBarsVaried_Other<k>, and of the chain
// BM_Command_Assemble_ClosedChain_Other<k>.
void BM_Command_AssembleJson_FourBars_Other(benchmark::State& state, const std::string& other) {
  time_process(state, other,
               {"assemble", fourbars_file(static_cast<int>(state.range(0))), "--json"});
}
void BM_Command_AssembleJson_FourBarsVaried_Other(benchmark::State& state,
                                                  const std::string& other) {
  time_process(state, other,
               {"assemble", fourbars_varied_file(static_cast<int>(state.range(0))), "--json"});
}
void BM_Command_Assemble_ClosedChain_Other(benchmark::State& state, const std::string& other) {
  std::vector<std::string> args{"assemble", closed_chain_file(static_cast<int>(state.range(0)))};
  if (state.range(1)) args.push_back("--json");
  time_process(state, other, args);
}
const int others_registered = [] {
  const char* list = std::getenv("DISPCON_BENCH_OTHER");
  int k = 0;
  for (std::string rest = list ? list : ""; !rest.empty(); ++k) {
    const size_t colon = rest.find(':');
    const std::string other = rest.substr(0, colon);
    rest = colon == std::string::npos ? "" : rest.substr(colon + 1);
    benchmark::RegisterBenchmark(
        ("BM_Command_AssembleJson_FourBars_Other" + std::to_string(k)).c_str(),
        BM_Command_AssembleJson_FourBars_Other, other)
        ->Arg(400)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(
        ("BM_Command_AssembleJson_FourBarsVaried_Other" + std::to_string(k)).c_str(),
        BM_Command_AssembleJson_FourBarsVaried_Other, other)
        ->Arg(400)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(
        ("BM_Command_Assemble_ClosedChain_Other" + std::to_string(k)).c_str(),
        BM_Command_Assemble_ClosedChain_Other, other)
        ->Args({100000, 0})
        ->Args({100000, 1})
        ->Iterations(2)
        ->UseManualTime()
        ->Unit(benchmark::kMillisecond);
  }
  return k;
}();
#endif

}  // namespace
