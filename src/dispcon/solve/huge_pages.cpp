#include "dispcon/solve/huge_pages.hpp"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace dispcon {

namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;

std::size_t round_up(std::size_t bytes) {
  return (bytes + kHugePage - 1) / kHugePage * kHugePage;
}

}  // namespace

#if defined(__linux__) && defined(MADV_HUGEPAGE)

// Maps a huge page more than asked and trims both ends, so the buffer starts on a 2 MB boundary
// (a huge page can only back an aligned 2 MB range).
void* map_huge(std::size_t bytes) {
  const std::size_t length = round_up(bytes);
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
  munmap(p, round_up(bytes));
}

#else

void* map_huge(std::size_t bytes) {
  return ::operator new (round_up(bytes), std::align_val_t{kHugePage});
}

void unmap_huge(void* p, std::size_t bytes) noexcept {
  ::operator delete (p, std::align_val_t{kHugePage});
}

#endif

}  // namespace dispcon
