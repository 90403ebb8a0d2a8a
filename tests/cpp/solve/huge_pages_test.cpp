// The huge-page allocator behind the solver's largest buffers: a buffer from kHugeBytes on
// starts on a 2 MB boundary (where a huge page can back it), smaller ones keep their type's
// alignment, a vector keeps its values as it grows across the threshold and shrinks back, and a
// buffer handed back serves the next one asked.
#include "dispcon/solve/huge_pages.hpp"

#include <gtest/gtest.h>

#include <cstdint>

#include "dispcon/math/rotation.hpp"

namespace dispcon {
namespace {

std::uintptr_t address(const void* p) {
  return reinterpret_cast<std::uintptr_t>(p);
}

TEST(HugePages, LargeBuffersStartOnAHugePage) {
  HugeVector<double> v(kHugeBytes / sizeof(double) + 3, 1.5);
  EXPECT_EQ(address(v.data()) % (std::size_t{2} << 20), 0u);
  EXPECT_EQ(v.front(), 1.5);
  EXPECT_EQ(v.back(), 1.5);
}

TEST(HugePages, SmallBuffersKeepTheirAlignment) {
  HugeVector<Quat> v(5, Quat::Identity());
  EXPECT_EQ(address(v.data()) % alignof(Quat), 0u);
  EXPECT_EQ(v[4].w(), 1.0);
}

TEST(HugePages, ValuesSurviveGrowingAcrossTheThresholdAndBack) {
  HugeVector<int> v;
  const int n = static_cast<int>(3 * kHugeBytes / sizeof(int));
  for (int i = 0; i < n; ++i) v.push_back(i);  // from operator new to mapped buffers
  long long sum = 0;
  for (int i = 0; i < n; ++i) sum += v[static_cast<size_t>(i)] == i;
  EXPECT_EQ(sum, n);
  v.resize(10);
  v.shrink_to_fit();  // back below the threshold
  for (int i = 0; i < 10; ++i) EXPECT_EQ(v[static_cast<size_t>(i)], i);
}

TEST(HugePages, ABufferHandedBackServesTheNextAsked) {
  // A size no other test asks for (buffers kept by earlier tests are other sizes, smaller).
  const std::size_t n = 9 * kHugeBytes / sizeof(double) + 1;
  const std::size_t length = 38u << 20;  // n doubles, in whole huge pages
  std::uintptr_t first = 0;
  const std::size_t before = kept_huge_bytes();
  {
    HugeVector<double> v(n, 2.5);
    first = address(v.data());
  }
  EXPECT_EQ(kept_huge_bytes(), before + length);
  HugeVector<double> same(n, 4.0);  // the kept buffer, its values written anew
  EXPECT_EQ(kept_huge_bytes(), before);
  EXPECT_EQ(address(same.data()), first);
  EXPECT_EQ(same.front(), 4.0);
  EXPECT_EQ(same.back(), 4.0);
  same = HugeVector<double>();
  EXPECT_EQ(kept_huge_bytes(), before + length);
  HugeVector<double> smaller(n / 2);  // the same buffer, trimmed; value-initialised
  EXPECT_EQ(kept_huge_bytes(), before);
  EXPECT_EQ(address(smaller.data()), first);
  EXPECT_EQ(smaller.front(), 0.0);
  EXPECT_EQ(smaller.back(), 0.0);
}

}  // namespace
}  // namespace dispcon
