#include "dispcon/solve/huge_pages.hpp"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>

#include <mutex>
#endif

namespace dispcon {

namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

std::size_t round_up(std::size_t bytes) {
  return (bytes + kHugePage - 1) / kHugePage * kHugePage;
}

}  // namespace

#if defined(__linux__) && defined(MADV_HUGEPAGE) && defined(MADV_FREE)

namespace {

// Buffers handed back are kept mapped for the next ones, up to kKeptBytes in kKeptBuffers, and
// advised MADV_FREE: the kernel may take their pages back when it needs memory (a reuse then
// faults in fresh ones, as a new mapping would), and otherwise a reuse writes into pages it
// already has. On the virtual machines the benchmarks run on, a fresh 2 MB page costs up to
// 2.3 ms of CPU on its first touch when the host has taken it back (freed guest memory is
// reported to the host), and the 100,000-link chain's solve maps about 150 MB: each solve of a
// large model paid that again, the same process's next solve now reuses its buffers.
constexpr std::size_t kKeptBytes = std::size_t{256} << 20;
constexpr int kKeptBuffers = 32;

struct Kept {
  std::mutex lock;
  void* at[kKeptBuffers] = {};
  std::size_t length[kKeptBuffers] = {};
  int count = 0;
  std::size_t bytes = 0;
};

Kept& kept() {
  static Kept* k = new Kept;  // never destroyed: buffers may be handed back during exit
  return *k;
}

// A kept buffer of at least `length` bytes (the smallest), trimmed to `length`; null if none.
void* take_kept(std::size_t length) {
  Kept& k = kept();
  std::lock_guard<std::mutex> hold(k.lock);
  int best = -1;
  for (int i = 0; i < k.count; ++i) {
    if (k.length[i] >= length && (best < 0 || k.length[i] < k.length[best])) best = i;
  }
  if (best < 0) return nullptr;
  void* p = k.at[best];
  const std::size_t extra = k.length[best] - length;
  k.bytes -= k.length[best];
  --k.count;
  k.at[best] = k.at[k.count];
  k.length[best] = k.length[k.count];
  if (extra > 0) munmap(static_cast<char*>(p) + length, extra);
  return p;
}

// Keeps a buffer of `length` bytes for a later map_huge(); false when there is no room.
bool keep(void* p, std::size_t length) {
  Kept& k = kept();
  std::lock_guard<std::mutex> hold(k.lock);
  if (k.count == kKeptBuffers || k.bytes + length > kKeptBytes) return false;
  madvise(p, length, MADV_FREE);
  k.at[k.count] = p;
  k.length[k.count] = length;
  ++k.count;
  k.bytes += length;
  return true;
}

}  // namespace

// Maps a huge page more than asked and trims both ends, so the buffer starts on a 2 MB boundary
// (a huge page can only back an aligned 2 MB range).
void* map_huge(std::size_t bytes) {
  const std::size_t length = round_up(bytes);
  if (void* p = take_kept(length)) return p;
  void* mapped =
      mmap(nullptr, length + kHugePage, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (mapped == MAP_FAILED) throw std::bad_alloc();
  const auto start = reinterpret_cast<std::uintptr_t>(mapped);
  const std::uintptr_t aligned = (start + kHugePage - 1) / kHugePage * kHugePage;
  if (aligned > start) munmap(mapped, aligned - start);
  const std::size_t tail = start + length + kHugePage - (aligned + length);
  if (tail > 0) munmap(reinterpret_cast<void*>(aligned + length), tail);
  void* p = reinterpret_cast<void*>(aligned);
  madvise(p, length, MADV_HUGEPAGE);  // advice only: without huge pages the buffer still works
  return p;
}

void unmap_huge(void* p, std::size_t bytes) noexcept {
  const std::size_t length = round_up(bytes);
  if (!keep(p, length)) munmap(p, length);
}

std::size_t kept_huge_bytes() {
  Kept& k = kept();
  std::lock_guard<std::mutex> hold(k.lock);
  return k.bytes;
}

#else

void* map_huge(std::size_t bytes) {
  return ::operator new (round_up(bytes), std::align_val_t{kHugePage});
}

void unmap_huge(void* p, std::size_t bytes) noexcept {
  ::operator delete (p, std::align_val_t{kHugePage});
}

std::size_t kept_huge_bytes() {
  return 0;
}

#endif

}  // namespace dispcon
