// `dispcon`: the command line over .dcl files (cli.md) and FreeCAD documents (fcstd.cpp). Parsing
// arguments and printing only; all the work is the engine's. Each subcommand lives in its own file
// (commands.hpp).
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
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

}  // namespace

int main(int argc, char** argv) {
  using namespace dispcon::cli;
  heap_on_huge_pages();
  // FreeCAD documents go to FreeCAD (fcstd.cpp).
  if (is_fcstd_call(argc, argv)) return run_fcstd(argc, argv);
  CLI::App app{
      "dispcon: mechanism assembly with displacement constraints (Gascuel & Gascuel 1994)"};
  app.require_subcommand(1);
  const std::vector<Subcommand> subcommands = {add_assemble(app), add_drag(app), add_animate(app),
                                               add_check(app), add_sweep(app)};
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
