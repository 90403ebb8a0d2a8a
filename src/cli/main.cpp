// `dispcon`: the command line over .dcl files (cli.md) and FreeCAD documents (fcstd.cpp). Parsing
// arguments and printing only; all the work is the engine's. Each subcommand lives in its own file
// (commands.hpp).
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "commands.hpp"

namespace {

// The process's heap on 2 MB pages where the kernel lends them (transparent huge pages in their
// "madvise" mode): a command touches a few MB once (the file, the model, the solver's buffers)
// and the first touch of each 4 kB page is a page fault. On the development machine (a VM) a
// fault costs 17-20 us of CPU: `assemble --json` of 400 four-bars made 1,250 of them, about half
// of its CPU time. So the heap gets one contiguous reserve at once (address space only: what is
// not touched costs nothing), advised as huge-page memory before anything in it is touched (a
// page touched first would give its 2 MB their 4 kB page table), and never handed back nor
// mapped apart for large blocks; the solver's threads share it. The heap's first, partial 2 MB
// (4 kB pages whatever the advice) are left to a block that is never used. Where huge pages are
// off, this changes nothing but the addresses.
void heap_on_huge_pages() {
  constexpr uintptr_t kHuge = uintptr_t{2} << 20;
  constexpr int kReserve = 256 << 20;
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // malloc's largest
  mallopt(M_TRIM_THRESHOLD, 1 << 30);   // above the reserve: never trimmed
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_TOP_PAD, kReserve);
  // The block that fills the partial 2 MB ends a page before the boundary (the next free chunk's
  // header is written just past it); the heap grows by the reserve as it is carved.
  const auto top = reinterpret_cast<uintptr_t>(std::malloc(64)) + 64;
  uintptr_t boundary = (top + kHuge - 1) & ~(kHuge - 1);
  if (boundary - top < 8192) boundary += kHuge;
  const uintptr_t size = boundary - top - 4096;
  void* const filler = std::malloc(size);
  mallopt(M_TOP_PAD, static_cast<int>(kHuge));
  if (!filler) return;
  const uintptr_t from = (reinterpret_cast<uintptr_t>(filler) + size + kHuge - 1) & ~(kHuge - 1);
  const uintptr_t end = reinterpret_cast<uintptr_t>(sbrk(0)) & ~(kHuge - 1);
  if (end > from) madvise(reinterpret_cast<void*>(from), end - from, MADV_HUGEPAGE);
}

// The subcommands, in the order --help lists them.
struct Registration {
  const char* name;
  dispcon::cli::Subcommand (*add)(CLI::App&);
};
constexpr Registration kSubcommands[] = {{"assemble", dispcon::cli::add_assemble},
                                         {"drag", dispcon::cli::add_drag},
                                         {"animate", dispcon::cli::add_animate},
                                         {"check", dispcon::cli::add_check},
                                         {"sweep", dispcon::cli::add_sweep}};

// The one subcommand a call names first, when no later argument names another: only it is set
// up. CLI11 builds each option with its validators and strings, and the four subcommands not run
// cost 0.43 M instructions a start. Otherwise (no subcommand first, as in --help, or another
// subcommand's name among the arguments) all are, as before: the help and error messages come
// from the same application either way.
const Registration* only_subcommand(int argc, char** argv) {
  if (argc < 2) return nullptr;
  const Registration* chosen = nullptr;
  for (const Registration& r : kSubcommands) {
    if (std::strcmp(argv[1], r.name) == 0) chosen = &r;
  }
  if (!chosen) return nullptr;
  for (int i = 2; i < argc; ++i) {
    for (const Registration& r : kSubcommands) {
      if (&r != chosen && std::strcmp(argv[i], r.name) == 0) return nullptr;
    }
  }
  return chosen;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace dispcon::cli;
  heap_on_huge_pages();
  // FreeCAD documents go to FreeCAD (fcstd.cpp).
  if (is_fcstd_call(argc, argv)) return run_fcstd(argc, argv);
  CLI::App app{
      "dispcon: mechanism assembly with displacement constraints (Gascuel & Gascuel 1994)"};
  app.require_subcommand(1);
  std::vector<Subcommand> subcommands;
  const Registration* only = only_subcommand(argc, argv);
  for (const Registration& r : kSubcommands) {
    if (!only || &r == only) subcommands.push_back(r.add(app));
  }
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
    for (const Subcommand& s : subcommands) {
      if (s.app->parsed()) return s.run();
    }
  } catch (const CLI::ValidationError& e) {
    std::cerr << "dispcon: error: " << e.what() << "\n";
    return kBadInput;
  } catch (const std::invalid_argument& e) {
    std::cerr << "dispcon: error: " << e.what() << "\n";
    return kBadInput;
  }
  return kBadInput;
}
