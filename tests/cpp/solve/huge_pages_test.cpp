// The huge-page allocator behind the solver's largest buffers: a buffer from kHugeBytes on
// starts on a 2 MB boundary (where a huge page can back it), smaller ones keep their type's
// alignment, and a vector keeps its values as it grows across the threshold and shrinks back.
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

}  // namespace
}  // namespace dispcon
