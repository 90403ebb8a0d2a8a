// Drag targets at the edge of reach: a gently curved chain of n unit links (link i turned by
// 0.02 sin(0.05 i) rad, the first pinned to the world) whose last link is dragged by its start
// point along x, as in docs/performance.md's 1,000-link case.
//   BM_DragStep_OutOfReach/<n>  one step held 0.02 beyond the n - 1 links' reach: told, not solved,
//                               with the nearest pose (the chain stretched toward the target)
//   BM_Pull_AlongStretch/<n>    a pull of the end by its start point moved along the circle 0.5
//                               beyond the n - 1 links' reach, 0.001 rad a frame (a mouse drag
//                               around the stretched chain): each frame the nearest pose
//   BM_Pull_CrankChain/<pixel>  the FreeCAD GUI test's 100-part drag (a chain of 50 cranks and 49
//                               couplers, one degree of freedom): a coupler's point pulled along
//                               its circle, 1.5 degrees a frame from 60 to 150 degrees and back,
//                               each frame from the last one's pose; pixel 0: the targets on the
//                               circle (in reach); pixel p: rounded to a grid of p thousandths
//                               (the GUI test's view from the top: 110), frames at the last
//                               one's point skipped, out of reach by up to half a pixel's diagonal
//   BM_DragStep_NearStretch/<n> the reachable step before it (0.04 short of full stretch), from
//                               the same curved pose each time
//   BM_DragStep_PastLimit       the robot arm's hand (samples/robot-arm.dcl) dragged toward
//                               (3, 0.5, 0) in 40 steps: the first step beyond its elbow's limit
//                               (the links would reach it), told out of reach with the nearest pose
//   BM_DragStep_PastLimitFar    the robot arm's hand held at (5, 0.5, 0), beyond its links' 2.5:
//                               the arm stretched toward it breaks the elbow's limit (never quite
//                               straight), so it is pulled to the nearest pose, 5 - 2 cos(0.1) away
//   BM_DragStep_DeadPoint       a crank-rocker four-bar's rocker tip (a hand pinned there) held in
//                               one step past its dead point: pulled to the dead point
//   BM_DragStep_OutOfPlane      a planar 2-link arm's hand held at (3, 2.5, 1): out of its plane
//                               and beyond its reach in it; pulled to the arm stretched in the
//                               plane
//   BM_DragStep_TurnPastLimit   that arm's hand on a wrist whose twist is kept within +-1 rad,
//                               turned 1.5 rad: out of reach by its rotation, 0.5 rad left
//   BM_DragStep_TurnAgainstCone the robot arm's hand turned 2.5 rad about z against its wrist's
//                               cone and twist: the swing stopped at the cone's edge
//   BM_DragStep_SnakeFar/<body> the flying snake (samples/snake.dcl, its tail sliding on a rod
//                               between x = -1 and 1) held by body 4, 5 or 6 (s3, s4, head) at
//                               (0, 10, 0), far out of reach: out_of_reach 1 when the step says
//                               so (its nearest pose: the links stretched up from the rod's
//                               middle), 0 when it fails otherwise (before the eighth round:
//                               stalled after 514-990 iterations, no pose)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common.hpp"
#include "dispcon/solve/solver.hpp"
#include "mechanisms.hpp"

namespace {

using namespace dispcon;

// A model from .dcl text, assembled; aborts when it does not load or assemble.
Model assembled(const char* text) {
  ParseResult r = parse_dcl(text);
  if (!r.ok()) {
    std::fprintf(stderr, "%s", r.messages().c_str());
    std::abort();
  }
  Model m = std::move(*r.model);
  if (!assemble(m).converged) std::abort();
  return m;
}

// One step of a drag to `target` that is out of reach, repeated (a failed step leaves the model
// as it was, so each repetition does the same work).
void out_of_reach_step(benchmark::State& state, Model& m, BodyId held, const Pose& at) {
  Dragger drag(m, held);
  int iterations = 0;
  double distance = 0;
  for (auto _ : state) {
    const SolveResult r = drag.move_to(at);
    if (r.status != SolveStatus::OutOfReach) state.SkipWithError(r.message.c_str());
    iterations = r.iterations;
    distance = r.distance_left + r.angle_left;
  }
  state.counters["iterations"] = iterations;
  state.counters["distance"] = distance;  // or the angle left (radians), out of reach by a turn
}

// The same, the body's origin held at `target` and its rotation as it is.
void out_of_reach_step(benchmark::State& state, Model& m, const std::string& body,
                       const Vec3& target) {
  const BodyId held = *m.find(body);
  Pose at = m.body(held).pose;
  at.x = target;
  out_of_reach_step(state, m, held, at);
}

Model curved_chain(int n) {
  Model m;
  BodyId last = Model::kWorld;
  Vec3 at = Vec3::Zero();
  for (int i = 1; i <= n; ++i) {
    const double a = 0.02 * std::sin(0.05 * i);
    Body b;
    b.name = "bar" + std::to_string(i);
    b.pose = Pose::from(at, Vec3(0, 0, a));
    b.center = Vec3(0.5, 0, 0);
    const BodyId id = m.add_body(b);
    Joint j;
    j.body1 = last;
    j.body2 = id;
    j.has_hinge = true;
    j.p1 = last == Model::kWorld ? Vec3::Zero() : Vec3(1, 0, 0);
    m.add_joint(j);
    at += Vec3(std::cos(a), std::sin(a), 0);
    last = id;
  }
  assemble(m);
  return m;
}

// The end's start point, held at x along the line through the pinned point and it.
Pose at_distance(const Pose& end, double x) {
  return Pose{end.q, end.x.normalized() * x};
}

void BM_DragStep_OutOfReach(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Model m = curved_chain(n);
  const BodyId end{n};
  Dragger drag(m, end);
  const Pose target = at_distance(m.body(end).pose, n - 1 + 0.02);
  int iterations = 0;
  for (auto _ : state) {
    const SolveResult r = drag.move_to(target);
    if (r.status != SolveStatus::OutOfReach) state.SkipWithError("not told out of reach");
    iterations = r.iterations;
  }
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_DragStep_OutOfReach)->Arg(2)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_Pull_AlongStretch(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Model m = curved_chain(n);
  const BodyId end{n};
  Puller pull(m, end, Vec3::Zero());
  const double radius = n - 1 + 0.5;
  double angle = 0;
  int iterations = 0;
  for (auto _ : state) {
    angle += 0.001;
    const SolveResult r = pull.pull_to(radius * Vec3(std::cos(angle), std::sin(angle), 0));
    if (r.status != SolveStatus::OutOfReach) state.SkipWithError(r.message.c_str());
    iterations = std::max(iterations, r.iterations);
  }
  state.counters["iterations"] = iterations;  // the most of any frame
}
BENCHMARK(BM_Pull_AlongStretch)->Arg(2)->Arg(1000)->Unit(benchmark::kMicrosecond);

void BM_Pull_CrankChain(benchmark::State& state) {
  const double pixel = 1e-3 * static_cast<double>(state.range(0));
  Model m = bench::crank_chain(50);
  if (!assemble(m).converged) std::abort();
  const BodyId grabbed = *m.find("coupler25");
  const Vec3 point(0.75, 0, 0.1);
  const Vec3 start = m.body(grabbed).pose.apply(point);
  // The frames' targets (the cursor's: each different from the last), then back again.
  std::vector<Vec3> path;
  const double a0 = M_PI / 3;
  for (int k = 1; k <= 60; ++k) {
    const double a = a0 + k * 1.5 * M_PI / 180;
    Vec3 to(std::cos(a) - std::cos(a0), std::sin(a) - std::sin(a0), 0);
    if (pixel > 0) {
      to.x() = pixel * std::round(to.x() / pixel);
      to.y() = pixel * std::round(to.y() / pixel);
    }
    if (path.empty() || path.back() != start + to) path.push_back(start + to);
  }
  for (size_t k = path.size() - 1; k-- > 1;) path.push_back(path[k]);
  Puller pull(m, grabbed, point);
  size_t frame = 0;
  int iterations = 0;
  for (auto _ : state) {
    const SolveResult r = pull.pull_to(path[frame++ % path.size()]);
    if (r.status != SolveStatus::Converged && r.status != SolveStatus::OutOfReach) {
      state.SkipWithError(r.message.c_str());
    }
    iterations += r.iterations;
  }
  // Newton steps a frame, and the frames of the path (there and back).
  state.counters["iterations"] = benchmark::Counter(iterations, benchmark::Counter::kAvgIterations);
  state.counters["frames"] = static_cast<double>(path.size());
}
BENCHMARK(BM_Pull_CrankChain)->Arg(0)->Arg(110)->Unit(benchmark::kMicrosecond);

void BM_DragStep_NearStretch(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  Model m = curved_chain(n);
  const BodyId end{n};
  const std::vector<Pose> start = m.poses();
  Dragger drag(m, end);
  const Pose target = at_distance(m.body(end).pose, n - 1 - 0.04);
  int iterations = 0;
  for (auto _ : state) {
    state.PauseTiming();
    m.set_poses(start);
    state.ResumeTiming();
    const SolveResult r = drag.move_to(target);
    if (!r.converged) state.SkipWithError(r.message.c_str());
    iterations = r.iterations;
  }
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_DragStep_NearStretch)->Arg(1000)->Iterations(3)->Unit(benchmark::kMillisecond);

void BM_DragStep_PastLimit(benchmark::State& state) {
  Model m = bench::sample("robot-arm.dcl");
  assemble(m);
  const BodyId hand = *m.find("hand");
  const Pose start = m.body(hand).pose;
  Pose away = start;
  away.x = Vec3(3, 0.5, 0);
  const int steps = 40;
  Dragger drag(m, hand);
  Pose target = start;
  for (int k = 1; k <= steps; ++k) {  // up to the first step out of reach
    const double t = static_cast<double>(k) / steps;
    target.x = (1 - t) * start.x + t * away.x;
    if (!drag.move_to(target).converged) break;
  }
  const std::vector<Pose> last = m.poses();
  int iterations = 0;
  for (auto _ : state) {
    const SolveResult r = drag.move_to(target);
    if (r.status != SolveStatus::OutOfReach) state.SkipWithError("not told out of reach");
    if (m.poses()[static_cast<size_t>(hand.value)].x != last[static_cast<size_t>(hand.value)].x)
      state.SkipWithError("a failed step moved the model");
    iterations = r.iterations;
  }
  state.counters["iterations"] = iterations;
}
BENCHMARK(BM_DragStep_PastLimit)->Unit(benchmark::kMicrosecond);

void BM_DragStep_PastLimitFar(benchmark::State& state) {
  Model m = bench::sample("robot-arm.dcl");
  assemble(m);
  out_of_reach_step(state, m, "hand", Vec3(5, 0.5, 0));
}
BENCHMARK(BM_DragStep_PastLimitFar)->Unit(benchmark::kMicrosecond);

// Ground 3, crank 1, coupler 3, rocker 2 (its tip B swings between the dead points |B| = 2 and
// |B| = 4, the latter at (3.5, 1.936)); the crank at 90 degrees, B on the upper branch. The hand
// held at (3.5, 0.866): 1 from the rocker's pivot, angularly past that dead point.
void BM_DragStep_DeadPoint(benchmark::State& state) {
  Model m = assembled(R"(
    object crank;   rotation 0 0 1.5708; center 0.5 0 0; end
    object coupler; position 0 1 0;     rotation 0 0 0.3377; center 1.5 0 0; end
    object rocker;  position 3 0 0;     rotation 0 0 1.656;  center 1 0 0; end
    object hand;    position 2.83 1.993 0; end
    constraint object2 crank;                    hinge 0 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
    constraint object1 crank;   object2 coupler; hinge 1 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
    constraint object1 coupler; object2 rocker;  hinge 3 0 0  2 0 0; angle 0 0 1 0 0 1 max 0; end
    constraint object2 rocker;                   hinge 3 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
    constraint object1 rocker;  object2 hand;    hinge 2 0 0  0 0 0; end
  )");
  out_of_reach_step(state, m, "hand", Vec3(3.5, 0.866025403784439, 0));
}
BENCHMARK(BM_DragStep_DeadPoint)->Unit(benchmark::kMicrosecond);

// Upper arm 2, forearm 1.5, revolutes about z; 3.5 stretched. `hand`: the hand and its joint to
// the forearm's end (bodies and joints keep the order of a file listing the hand third).
Model planar_arm(const char* hand) {
  const std::string text = std::string(R"(
    object upper;   rotation 0 0 0.3; center 1 0 0; end
    object forearm; position 1.9107 0.5910 0; rotation 0 0 1.5; center 0.75 0 0; end
    constraint object2 upper;                    hinge 0 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
    constraint object1 upper;   object2 forearm; hinge 2 0 0  0 0 0; angle 0 0 1 0 0 1 max 0; end
  )") + hand;
  return assembled(text.c_str());
}

void BM_DragStep_OutOfPlane(benchmark::State& state) {
  Model m = planar_arm(R"(
    object hand;    position 2.0168 2.0873 0; end
    constraint object1 forearm; object2 hand;    hinge 1.5 0 0  0 0 0; end
  )");
  out_of_reach_step(state, m, "hand", Vec3(3, 2.5, 1));
}
BENCHMARK(BM_DragStep_OutOfPlane)->Unit(benchmark::kMicrosecond);

// The same arm with a hand on a wrist whose twist is kept within +-1 rad, held where it is and
// turned 1.5 rad about z: out of reach by its rotation, 0.5 rad left.
void BM_DragStep_TurnPastLimit(benchmark::State& state) {
  Model m = planar_arm(R"(
    object hand;    position 2.0168 2.0873 0; rotation 0 0 1.5; center 0.25 0 0; end
    constraint object1 forearm; object2 hand;    hinge 1.5 0 0  0 0 0; angle 0 0 1 0 0 1 max 0;
      twist 1 0 0 1 0 0 min -1 max 1; end
  )");
  const BodyId hand = *m.find("hand");
  Pose at = m.body(hand).pose;
  at.q = (Quat(Eigen::AngleAxisd(1.5, Vec3::UnitZ())) * at.q).normalized();
  out_of_reach_step(state, m, hand, at);
}
BENCHMARK(BM_DragStep_TurnPastLimit)->Unit(benchmark::kMicrosecond);

// The robot arm's hand held where it is and turned 2.5 rad about z, against its wrist's cone
// (0.5 rad) and twist (+-1 rad): out of reach by its rotation, the swing stopped at the cone's
// edge (466 iterations and no pose before the seventh round of issue 14).
void BM_DragStep_TurnAgainstCone(benchmark::State& state) {
  Model m = bench::sample("robot-arm.dcl");
  assemble(m);
  const BodyId hand = *m.find("hand");
  Pose at = m.body(hand).pose;
  at.q = (Quat(Eigen::AngleAxisd(2.5, Vec3::UnitZ())) * at.q).normalized();
  out_of_reach_step(state, m, hand, at);
}
BENCHMARK(BM_DragStep_TurnAgainstCone)->Unit(benchmark::kMicrosecond);

void BM_DragStep_SnakeFar(benchmark::State& state) {
  Model m = bench::sample("snake.dcl");
  assemble(m);
  const BodyId held{static_cast<int>(state.range(0))};
  Pose at = m.body(held).pose;
  at.x = Vec3(0, 10, 0);
  Dragger drag(m, held);
  int iterations = 0;
  bool out = false;
  double distance = 0;
  for (auto _ : state) {
    const SolveResult r = drag.move_to(at);
    iterations = r.iterations;
    out = r.status == SolveStatus::OutOfReach;
    distance = r.distance_left;
  }
  state.counters["iterations"] = iterations;
  state.counters["out_of_reach"] = out;
  state.counters["distance"] = distance;
}
BENCHMARK(BM_DragStep_SnakeFar)->DenseRange(4, 6)->Unit(benchmark::kMicrosecond);

}  // namespace
