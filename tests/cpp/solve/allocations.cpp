// The iteration loop allocates nothing: a solve's allocations (its result: reports, poses,
// message) do not depend on how many iterations it took. Its own binary, since it replaces
// malloc to count calls (glibc lets a program interpose it).
#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <cstdlib>
#include <map>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/solve/solver.hpp"

extern "C" void* __libc_malloc(size_t size);
extern "C" void* __libc_calloc(size_t count, size_t size);
extern "C" void* __libc_realloc(void* p, size_t size);
extern "C" void* __libc_memalign(size_t alignment, size_t size);

namespace {
std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
void count() {
  if (counting.load(std::memory_order_relaxed)) allocations.fetch_add(1);
}
}  // namespace

// Every way into the heap: an over-aligned operator new (the solver's PoseBuffer, HugeVector)
// goes through aligned_alloc, not malloc, and was not counted (a turn's pull made one such
// allocation a step, unseen).
extern "C" void* malloc(size_t size) {
  count();
  return __libc_malloc(size);
}
extern "C" void* calloc(size_t n, size_t size) {
  count();
  return __libc_calloc(n, size);
}
extern "C" void* realloc(void* p, size_t size) {
  count();
  return __libc_realloc(p, size);
}
extern "C" void* aligned_alloc(size_t alignment, size_t size) {
  count();
  return __libc_memalign(alignment, size);
}
extern "C" void* memalign(size_t alignment, size_t size) {
  count();
  return __libc_memalign(alignment, size);
}
extern "C" int posix_memalign(void** p, size_t alignment, size_t size) {
  count();
  *p = __libc_memalign(alignment, size);
  return *p ? 0 : ENOMEM;
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

// A drag step's turn out of reach along a cone's rim runs its reduced quasi-Newton steps
// (rim.cpp): once warm they allocate nothing, so the robot arm's hand turned further and further
// about z against its wrist's cone (0.5 rad) and twist allocates as much a step whatever its
// iterations (24 to 30 here; 89 allocations each, the result's and the pull's own; 261, 286 and
// 311 before issue 14's fifteenth round: Eigen's dynamic matrices made and freed in each rim
// step, and the model made again at each pull).
TEST(Allocations, TurnsAlongARimAllocateTheSameWhateverTheirIterations) {
  ParseResult parsed = load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/robot-arm.dcl");
  ASSERT_TRUE(parsed.ok()) << parsed.messages();
  Model m = std::move(*parsed.model);
  ASSERT_TRUE(assemble(m).converged);
  const BodyId hand = *m.find("hand");
  const Pose start = m.body(hand).pose;
  Dragger drag(m, hand);
  std::map<int, long> by_iterations;  // iterations of a step -> allocations it made
  for (int k = 0; k <= 16; ++k) {
    const double angle = 2.0 + 0.05 * k;
    const Pose target{(Quat(Eigen::AngleAxisd(angle, Vec3::UnitZ())) * start.q).normalized(),
                      start.x};
    allocations = 0;
    counting = true;
    const SolveResult r = drag.move_to(target);
    counting = false;
    ASSERT_EQ(r.status, SolveStatus::OutOfReach) << "turned " << angle << ": " << r.message;
    if (k > 2) by_iterations.emplace(r.iterations, allocations.load());  // warm by then
  }
  ASSERT_GE(by_iterations.size(), 2u) << "every step took the same number of iterations";
  for (const auto& [iterations, count] : by_iterations) {
    EXPECT_EQ(count, by_iterations.begin()->second)
        << iterations << " iterations made " << count << " allocations, "
        << by_iterations.begin()->first << " made " << by_iterations.begin()->second;
  }
}

// A pull whose iterations are bounded (a drag step's turn: Session::pull's all_iterations) keeps
// the last valid poses it met, in a buffer of the session's: once warm it allocates what the
// same pull unbounded allocates (it kept them in a buffer of its own, one allocation a turn's
// step, issue 14's thirteenth round; over-aligned, so the count above did not see it).
TEST(Allocations, BoundedPullsAllocateAsUnboundedOnes) {
  ParseResult parsed = load_dcl(std::string(DISPCON_SOURCE_DIR) + "/samples/robot-arm.dcl");
  ASSERT_TRUE(parsed.ok()) << parsed.messages();
  Model m = std::move(*parsed.model);
  ASSERT_TRUE(assemble(m).converged);
  const BodyId hand = *m.find("hand");
  Joint pull;  // the hand's origin drawn to a point in reach, as a Puller does
  pull.body2 = hand;
  pull.has_hinge = true;
  pull.label = "pull";
  const JointId joint = m.add_joint(pull);
  m.set_hinge(joint, m.body(hand).pose.x + Vec3(0.2, -0.1, 0.05), std::nullopt);
  Session session(m, SolveOptions{});
  long counted[2] = {0, 0};
  int iterations[2] = {0, 0};
  for (int k = 0; k < 6; ++k) {
    const int bounded = k % 2;
    std::vector<Pose> poses = m.poses();
    allocations = 0;
    counting = true;
    const SolveResult r = session.pull(poses, joint, -1, bounded ? 1000 : -1);
    counting = false;
    ASSERT_TRUE(r.converged || r.status == SolveStatus::OutOfReach) << r.message;
    ASSERT_GT(r.iterations, 1);
    counted[bounded] = allocations.load();  // the last of each: warm
    iterations[bounded] = r.iterations;
  }
  EXPECT_EQ(iterations[1], iterations[0]) << "the bound changed the pull";
  EXPECT_EQ(counted[1], counted[0]) << "bounded " << counted[1] << ", unbounded " << counted[0];
}

}  // namespace
}  // namespace dispcon
