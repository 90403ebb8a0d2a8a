// The iteration loop allocates nothing: a solve's allocations (its result: reports, poses,
// message) do not depend on how many iterations it took. Its own binary, since it replaces
// malloc to count calls (glibc lets a program interpose it).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <map>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/solve/solver.hpp"

extern "C" void* __libc_malloc(size_t size);

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
}  // namespace

extern "C" void* malloc(size_t size) {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
  return __libc_malloc(size);
}

namespace dispcon {
namespace {

TEST(Allocations, DragStepsAllocateTheSameWhateverTheirIterations) {
  ParseResult parsed = load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/monocycle.dcl");
  ASSERT_TRUE(parsed.ok()) << parsed.messages();
  Model m = std::move(*parsed.model);
  ASSERT_TRUE(assemble(m).converged);
  const BodyId wheel = *m.find("wheel");
  const Pose w = m.body(wheel).pose;
  const Vec3 axle = w.q * Vec3::UnitX();
  Dragger pedal(m, wheel);
  std::map<int, long> by_iterations;  // iterations of a step -> allocations it made
  for (int k = 1; k <= 400; ++k) {
    Pose p = w;
    p.q = quat_from_rotation_vector(axle * (0.01 * k)) * w.q;
    allocations = 0;
    counting = true;
    const SolveResult r = pedal.move_to(p);
    counting = false;
    ASSERT_TRUE(r.converged) << "step " << k << ": " << r.message;
    if (k > 2) by_iterations.emplace(r.iterations, allocations.load());  // warm by then
  }
  ASSERT_GE(by_iterations.size(), 2u) << "every step took the same number of iterations";
  for (const auto& [iterations, count] : by_iterations) {
    EXPECT_EQ(count, by_iterations.begin()->second)
        << iterations << " iterations made " << count << " allocations, "
        << by_iterations.begin()->first << " made " << by_iterations.begin()->second;
  }
}

}  // namespace
}  // namespace dispcon
