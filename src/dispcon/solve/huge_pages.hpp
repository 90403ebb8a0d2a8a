// Large working buffers on huge pages. Fresh memory costs a page fault on its first touch, one
// every 4 KB: on the machine the benchmarks run on, about 4 ms of CPU a megabyte, so the tens of
// megabytes of bodies and rows of a 100,000-link chain cost its solve more in faults than in
// arithmetic. A buffer of kHugeBytes and more is mapped on its own, 2 MB aligned, and advised
// MADV_HUGEPAGE: where transparent huge pages are allowed ("madvise" or "always"), the kernel
// backs it with 2 MB pages, a fault each. Smaller buffers come from operator new as usual.
#pragma once

#include <cstddef>
#include <new>
#include <vector>

namespace dispcon {

inline constexpr std::size_t kHugeBytes = std::size_t{4} << 20;

// `bytes` (at least kHugeBytes) of memory, 2 MB aligned, advised huge; std::bad_alloc
// when it cannot be mapped. Handed back with unmap_huge and the same `bytes`, which keeps up to
// 256 MB of such buffers mapped (advised MADV_FREE, so the kernel may take their pages when it
// needs them) for the next map_huge calls of the process: a large model's next solve writes
// into pages it already has instead of faulting in fresh ones.
void* map_huge(std::size_t bytes);
void unmap_huge(void* p, std::size_t bytes) noexcept;
// The bytes of the buffers kept for reuse now (for tests).
std::size_t kept_huge_bytes();

// A standard allocator: huge pages from kHugeBytes on, operator new below (the size decides
// both ways, so allocate and deallocate agree).
template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() noexcept = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugeBytes) return static_cast<T*>(map_huge(bytes));
    return static_cast<T*>(::operator new (bytes, std::align_val_t{alignof(T)}));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    const std::size_t bytes = n * sizeof(T);
    if (bytes >= kHugeBytes) {
      unmap_huge(p, bytes);
    } else {
      ::operator delete (p, std::align_val_t{alignof(T)});
    }
  }
  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
  template <typename U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept {
    return false;
  }
};

template <typename T>
using HugeVector = std::vector<T, HugePageAllocator<T>>;

}  // namespace dispcon
