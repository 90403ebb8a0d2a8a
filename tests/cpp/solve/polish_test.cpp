// The Newton polish of large groups (sparse systems), checked against properties every answer
// must have; and small groups (dense systems) solved one after another as each alone. A grid of
// unit links pinned at lattice nodes (loops sharing bodies: the saddle-point form) is made of
// four-bars with four equal sides, so every cell is a rhombus: the verticals of a row stay
// parallel, and so do the horizontals of a level. A free closed chain of masses (a few rows per
// body: J M^-1 J^T itself) keeps its centre of mass, since every correction is a pair of opposite
// impulses (seed 4.2, footnote 5).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "dispcon/model/joint_kinds.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {
namespace {

struct Grid {
  Model model;
  std::vector<std::vector<BodyId>> vertical;    // [row][col], row r links level r to r + 1
  std::vector<std::vector<BodyId>> horizontal;  // [level][col], level 1 .. n, col to col + 1
};

// n x n cells of unit links from a rough lattice; links are hinged about z at the nodes, the
// bottom nodes on the ground.
Grid grid(int n) {
  Grid g;
  Model& m = g.model;
  auto node = [](int r, int c) {
    return Vec3(c + 0.05 * std::sin(3.0 * r + c), r + 0.05 * std::cos(r + 2.0 * c), 0);
  };
  const size_t side = static_cast<size_t>(n + 1);
  std::vector<std::vector<BodyId>> pin(side, std::vector<BodyId>(side, Model::kWorld));
  std::vector<std::vector<Vec3>> local(side, std::vector<Vec3>(side));
  for (int c = 0; c <= n; ++c) local[0][static_cast<size_t>(c)] = Vec3(c, 0, 0);
  auto attach = [&](int r, int c, BodyId link, const Vec3& at) {
    BodyId& p = pin[static_cast<size_t>(r)][static_cast<size_t>(c)];
    if (r == 0 || p != Model::kWorld) {
      Joint j;
      j.body1 = p;
      j.body2 = link;
      j.has_hinge = true;
      j.p1 = local[static_cast<size_t>(r)][static_cast<size_t>(c)];
      j.p2 = at;
      j.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
      m.add_joint(j);
    } else {
      p = link;
      local[static_cast<size_t>(r)][static_cast<size_t>(c)] = at;
    }
  };
  int count = 0;
  auto link = [&](int r0, int c0, int r1, int c1) {
    const Vec3 a = node(r0, c0), b = node(r1, c1);
    Body body;
    body.name = "k" + std::to_string(count++);
    body.pose = Pose::from(a, Vec3(0, 0, std::atan2(b.y() - a.y(), b.x() - a.x())));
    const BodyId id = m.add_body(body);
    attach(r0, c0, id, Vec3::Zero());
    attach(r1, c1, id, Vec3(1, 0, 0));
    return id;
  };
  g.vertical.resize(static_cast<size_t>(n));
  g.horizontal.resize(static_cast<size_t>(n + 1));
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c <= n; ++c) g.vertical[static_cast<size_t>(r)].push_back(link(r, c, r + 1, c));
    for (int c = 0; c < n; ++c) {
      g.horizontal[static_cast<size_t>(r + 1)].push_back(link(r + 1, c, r + 1, c + 1));
    }
  }
  return g;
}

Vec3 direction(const Model& m, BodyId b) {
  return m.body(b).pose.q * Vec3::UnitX();
}

// Largest angle between the first link of each list and the others.
double spread(const Model& m, const std::vector<std::vector<BodyId>>& lists) {
  double worst = 0;
  for (const std::vector<BodyId>& list : lists) {
    for (BodyId b : list) {
      const Vec3 d0 = direction(m, list.front()), d = direction(m, b);
      worst = std::max(worst, std::atan2(d0.cross(d).norm(), d0.dot(d)));
    }
  }
  return worst;
}

// A four-bar (the benchmark's: crank fixed, coupler and rocker from a rough start) at height z;
// `reversed` lists its three joints the other way round: the same rows joining other unknowns in
// turn. Returns its moving bodies.
std::vector<BodyId> add_fourbar(Model& m, double z, bool reversed, const std::string& name) {
  auto body = [&](const char* part, Vec3 x, double turn, bool fixed) {
    Body b;
    b.name = part + name;
    b.pose = Pose::from(x + Vec3(0, 0, z), Vec3(0, 0, turn));
    b.fixed = fixed;
    return m.add_body(b);
  };
  const BodyId crank = body("crank", Vec3::Zero(), 0.7, true);
  const BodyId coupler = body("coupler", Vec3(0.7648, 0.6442, 0), 0.757, false);
  const BodyId rocker = body("rocker", Vec3(3, 0, 0), 1.951, false);
  // The joint kinds' table's revolute about z (the anchors' default axis).
  auto revolute = [](BodyId b1, BodyId b2, Vec3 p1, Vec3 p2) {
    return dispcon::revolute(b1, Anchor{p1}, b2, Anchor{p2});
  };
  std::vector<Joint> joints = {revolute(crank, coupler, Vec3(1, 0, 0), Vec3::Zero()),
                               revolute(coupler, rocker, Vec3(3, 0, 0), Vec3(2.5, 0, 0)),
                               revolute(Model::kWorld, rocker, Vec3(3, 0, z), Vec3::Zero())};
  if (reversed) std::swap(joints.front(), joints.back());
  for (const Joint& j : joints) m.add_joint(j);
  return {coupler, rocker};
}

bool same_bits(const Pose& a, const Pose& b) {
  return std::memcmp(a.x.data(), b.x.data(), 3 * sizeof(double)) == 0 &&
         std::memcmp(a.q.coeffs().data(), b.q.coeffs().data(), 4 * sizeof(double)) == 0;
}

// Small groups share one thread's scratch space, where a group's step reuses what the last step
// listed of its rows while they join the same unknowns: groups of the same size but another
// order of joints, or another size, must list theirs anew. Solved together on one thread, each
// lands where it lands solved alone, bit for bit.
TEST(DensePolish, GroupsSolvedTogetherAsEachAlone) {
  const std::vector<bool> order = {false, true, false, true};
  Model together;
  std::vector<std::vector<BodyId>> moving;
  for (size_t k = 0; k < order.size(); ++k) {
    moving.push_back(add_fourbar(together, 10.0 * k, order[k], std::to_string(k)));
  }
  Body lone;  // a pendulum: a group of five rows between the four-bars' fifteen
  lone.name = "pendulum";
  lone.pose = Pose::from(Vec3(0.1, -1, 50), Vec3(0, 0, 0.2));
  const BodyId pendulum = together.add_body(lone);
  Joint pin;
  pin.body1 = Model::kWorld;
  pin.body2 = pendulum;
  pin.has_hinge = true;
  pin.p1 = Vec3(0, 0, 50);
  pin.p2 = Vec3(0, 1, 0);
  pin.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
  together.add_joint(pin);
  moving.push_back(add_fourbar(together, 60, false, "last"));
  SolveOptions o;
  o.threads = 1;
  const SolveResult all = assemble(together, o);
  ASSERT_TRUE(all.converged) << all.message;
  EXPECT_GT(all.polish_iterations, 1);
  for (size_t k = 0; k < moving.size(); ++k) {
    Model alone;
    const bool last = k + 1 == moving.size();
    const std::vector<BodyId> mine = add_fourbar(alone, last ? 60 : 10.0 * k, !last && order[k],
                                                 last ? "last" : std::to_string(k));
    ASSERT_TRUE(assemble(alone, o).converged);
    for (size_t b = 0; b < mine.size(); ++b) {
      EXPECT_TRUE(same_bits(alone.body(mine[b]).pose, together.body(moving[k][b]).pose))
          << "four-bar " << k << ", body " << b;
    }
  }
}

// The rocker's turn about z where add_fourbar's linkage closes (crank fixed at 0.7 rad, length
// 1; coupler 3; rocker 2.5 from its pivot at (3, 0)): the coupler's far end on both circles, the
// one on the side of the rough start.
double closed_rocker_turn() {
  const Vec3 a(std::cos(0.7), std::sin(0.7), 0), pivot(3, 0, 0);
  const Vec3 d = pivot - a;
  const double l = d.norm(), along = (9 - 6.25 + l * l) / (2 * l),
               off = std::sqrt(9 - along * along);
  const Vec3 mid = a + along / l * d, normal(-d.y() / l, d.x() / l, 0);
  double best = 0, nearest = 1e9;
  for (double side : {-1.0, 1.0}) {
    const Vec3 b = mid + side * off * normal;
    const double turn = std::atan2(b.y() - pivot.y(), b.x() - pivot.x());
    if (std::abs(turn - 1.951) < nearest) nearest = std::abs(turn - 1.951), best = turn;
  }
  return best;
}

double turn_about_z(const Pose& p) {
  const Vec3 x = p.q * Vec3::UnitX();
  return std::atan2(x.y(), x.x());
}

// A small group whose rows leave no free motion (the crank fixed: the four-bar's poses are
// isolated, three of its fifteen rows redundant) takes a chord step for its last step, the
// factorisation of the step before reused: it lands on the same answer as Newton's steps, to
// within the residual it leaves (about 2e-10, where a fourth Newton step leaves 2.5e-14).
TEST(DensePolish, ChordStepWithoutFreeMotionLandsOnTheAnswer) {
  Model m;
  const std::vector<BodyId> moving = add_fourbar(m, 0, false, "");
  SolveOptions o;
  o.record_history = true;
  const SolveResult r = assemble(m, o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.iterations, 5);
  EXPECT_LE(r.max_residual, o.tolerance);
  EXPECT_GT(r.history.back(), 1e-12) << "the last step was not a chord step";
  EXPECT_NEAR(turn_about_z(m.body(moving[1]).pose), closed_rocker_turn(), 1e-9);
}

// With free motion (the crank let go about its pivot) a chord step would lie in the old rows'
// span and slide the poses along the free motion: every step stays a Newton step, which closes
// in quadratically (its last residual far below a chord step's).
TEST(DensePolish, NoChordStepWithFreeMotion) {
  Model m;
  add_fourbar(m, 0, false, "");
  Body crank = m.body(BodyId{1});
  ASSERT_EQ(crank.name, "crank");
  ASSERT_TRUE(crank.fixed);
  Model free;
  for (int i = 1; i < m.body_count(); ++i) {
    Body b = m.body(BodyId{i});
    b.fixed = false;
    free.add_body(b);
  }
  for (int i = 0; i < m.joint_count(); ++i) free.add_joint(m.joint(JointId{i}));
  free.add_joint(
      dispcon::revolute(Model::kWorld, Anchor{Vec3::Zero()}, BodyId{1}, Anchor{Vec3::Zero()}));
  SolveOptions o;
  o.record_history = true;
  const SolveResult r = assemble(free, o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LT(r.history.back(), 1e-12) << "a chord step was taken with free motion";
}

TEST(SparsePolish, GridOfFourBarsAssemblesIntoRhombi) {
  Grid g = grid(6);  // 78 links, 570 rows: solved sparse
  SolveOptions o;
  o.tolerance = 1e-10;
  const SolveResult r = assemble(g.model, o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LE(r.max_residual, 1e-10);
  EXPECT_LT(spread(g.model, g.vertical), 1e-8);
  EXPECT_LT(spread(g.model, g.horizontal), 1e-8);
  for (const std::vector<BodyId>& level : g.horizontal) {
    for (BodyId b : level) EXPECT_NEAR(g.model.body(b).pose.x.z(), 0, 1e-9);
  }
}

TEST(SparsePolish, DraggedVerticalShearsItsRow) {
  Grid g = grid(6);
  ASSERT_TRUE(assemble(g.model).converged);
  const BodyId first = g.vertical[0][0];
  const Vec3 d0 = direction(g.model, first);
  const double start = std::atan2(d0.y(), d0.x());
  Pose target = g.model.body(first).pose;
  target.q = quat_from_rotation_vector(Vec3(0, 0, -0.3)) * target.q;
  const DragResult d = drag(g.model, first, target, 15);
  ASSERT_TRUE(d.converged) << d.message;
  // Every vertical of the bottom row turned with the dragged one: the row sheared as a whole.
  for (BodyId b : g.vertical[0]) {
    const Vec3 v = direction(g.model, b);
    EXPECT_NEAR(std::atan2(v.y(), v.x()), start - 0.3, 1e-8);
  }
  EXPECT_LT(spread(g.model, g.vertical), 1e-8);
  EXPECT_LT(spread(g.model, g.horizontal), 1e-8);
}

// A drag frame's first measure takes the joints whose bodies did not move from the last frame's
// measure; a hinge moved between frames (set_hinge makes no new revision of the model) is
// measured anew.
TEST(SparsePolish, DragSeesAHingeMovedBetweenFrames) {
  Grid g = grid(6);
  ASSERT_TRUE(assemble(g.model).converged);
  const BodyId first = g.vertical[0][0];
  Pose target = g.model.body(first).pose;
  target.q = quat_from_rotation_vector(Vec3(0, 0, -0.01)) * target.q;
  Dragger drag(g.model, first);
  ASSERT_TRUE(drag.move_to(target).converged);
  const SolveResult still = drag.move_to(target);
  ASSERT_TRUE(still.converged) << still.message;
  EXPECT_EQ(still.iterations, 0) << "nothing moved";
  const JointId far{g.model.joint_count() - 1};
  const Joint& j = g.model.joint(far);
  ASSERT_TRUE(j.body1 != first && j.body2 != first);
  g.model.set_hinge(far, std::nullopt, j.p2 + Vec3(0.001, 0, 0));
  const SolveResult moved = drag.move_to(target);
  ASSERT_TRUE(moved.converged) << moved.message;
  EXPECT_GT(moved.iterations, 0);
  for (const ConstraintReport& c : measure(g.model, g.model.poses(), SolveOptions{})) {
    EXPECT_LE(c.residual, 1e-9) << "joint " << c.joint.value;
  }
}

// A closed ring of n links of masses hinged about z, none fixed, from a perturbed circle.
Model free_ring(int n, std::vector<BodyId>& ids) {
  Model m;
  const double R = n / (2 * kPi), L = 2 * R * std::sin(kPi / n);
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    Body b;
    b.name = "l" + std::to_string(i);
    b.pose = Pose::from(Vec3(R * std::cos(a) + 0.02 * std::sin(7.0 * i),
                             R * std::sin(a) + 0.02 * std::cos(3.0 * i), 0.02 * std::sin(5.0 * i)),
                        Vec3(0, 0, a + kPi / 2 + kPi / n));
    b.center = Vec3(L / 2, 0, 0);
    b.mass = 1 + 0.5 * std::sin(i);
    b.inertia = Vec3(0.01, 0.1, 0.1).asDiagonal() * *b.mass;
    ids.push_back(m.add_body(b));
  }
  for (int i = 0; i < n; ++i) {
    Joint j;
    j.body1 = ids[static_cast<size_t>(i)];
    j.body2 = ids[static_cast<size_t>((i + 1) % n)];
    j.has_hinge = true;
    j.p1 = Vec3(L, 0, 0);
    m.add_joint(j);
  }
  return m;
}

TEST(SparsePolish, FreeClosedChainKeepsItsCentreOfMass) {
  const int n = 60;  // 180 rows: solved sparse
  std::vector<BodyId> ids;
  Model m = free_ring(n, ids);
  const double R = n / (2 * kPi);
  auto centre = [&] {
    Vec3 sum = Vec3::Zero();
    double mass = 0;
    for (BodyId b : ids) {
      sum += *m.body(b).mass * m.body(b).world_center();
      mass += *m.body(b).mass;
    }
    return Vec3(sum / mass);
  };
  const Vec3 before = centre();
  SolveOptions o;
  o.tolerance = 1e-10;
  const SolveResult r = assemble(m, o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_GT(r.polish_iterations, 0);
  EXPECT_LT((centre() - before).norm(), 1e-12 * R);
}

// A large chain's measure after a step gathers the next step's rows with the residuals; a
// drag's next frame moves the held body, so its first step must gather them anew: every frame
// of small moves is one Newton step (rows of the frame before would give a step that gains
// nothing, and a second one). The held body leaves one group (the rest of the ring), whose last
// measure in a frame is the last gather before the next.
TEST(SparsePolish, DraggedChainTakesOneStepAFrame) {
  const int n = 100;  // 300 rows, J M^-1 J^T
  std::vector<BodyId> ids;
  Model m = free_ring(n, ids);
  ASSERT_TRUE(assemble(m).converged);
  const BodyId held = ids[n / 2];
  const Pose start = m.body(held).pose;
  Dragger drag(m, held);
  for (int k = 1; k <= 10; ++k) {
    Pose target = start;
    target.x.z() += 0.002 * std::sin(0.01 * k);  // as BM_DragStep_ClosedChain
    const SolveResult r = drag.move_to(target);
    ASSERT_TRUE(r.converged) << r.message;
    EXPECT_EQ(r.iterations, 1) << "frame " << k;
    for (const ConstraintReport& c : measure(m, m.poses(), SolveOptions{})) {
      EXPECT_LE(c.residual, 1e-9) << "frame " << k << ", joint " << c.joint.value;
    }
  }
}

}  // namespace
}  // namespace dispcon
