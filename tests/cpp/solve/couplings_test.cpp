// Couplings in mechanisms against their analytic answers: gear trains hold their ratio through
// full turns, a planetary set obeys Willis' formula, a rack travels radius times the pinion's turn,
// a screw advances its pitch per turn, gears in a closed loop with a linkage drag without a jump,
// and the degrees of freedom come out as the textbook counts them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "dispcon/io/dcl_reader.hpp"
#include "dispcon/parts/coupling.hpp"
#include "dispcon/solve/diagnostics.hpp"
#include "dispcon/solve/solver.hpp"
#include "support/samples.hpp"

namespace dispcon {
namespace {

using test_support::id;
using test_support::sample;

SolveOptions tight() {
  SolveOptions o;
  o.tolerance = 1e-13;
  return o;
}

// A body's turn about a world axis, unwrapped from one call to the next.
class Turn {
 public:
  Turn(const Model& m, const char* name, const Vec3& axis = Vec3::UnitZ())
      : m_(m), body_(id(m, name)), axis_(axis), start_(raw()), last_(start_) {}
  // The turn since construction (radians), taking each step the short way round.
  double operator()() {
    const double r = raw();
    total_ += std::remainder(r - last_, 2 * kPi);
    last_ = r;
    return total_;
  }

 private:
  double raw() const {
    Vec3 e1, e2;
    e1 = axis_.unitOrthogonal();
    e2 = axis_.cross(e1);
    const Vec3 v = m_.body(body_).pose.q * e1;
    return std::atan2(v.dot(e2), v.dot(e1));
  }
  const Model& m_;
  BodyId body_;
  Vec3 axis_;
  double start_, last_;
  double total_ = 0;
};

// For RecordProperty: the figure in scientific notation.
std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

Pose turned(const Vec3& position, const Vec3& axis, double angle) {
  return Pose::from(position, angle * axis);
}

TEST(Couplings, ThreeGearTrainHoldsItsRatioThroughTwoFullTurns) {
  Model m = sample("three-gears.dcl");
  EXPECT_EQ(check(m).dof, 1);
  Dragger drag(m, id(m, "g1"), tight());
  Turn g2(m, "g2"), g3(m, "g3");
  double worst = 0;
  const int steps = 720;  // 1 degree per step
  for (int k = 1; k <= steps; ++k) {
    const double t = 4 * kPi * k / steps;
    ASSERT_TRUE(drag.move_to(turned(Vec3::Zero(), Vec3::UnitZ(), t)).converged) << "step " << k;
    worst = std::max({worst, std::abs(g2() + 0.5 * t), std::abs(g3() - 2.0 / 3.0 * t)});
  }
  RecordProperty("ratio_error", sci(worst));
  EXPECT_LT(worst, 1e-12);
  // Two turns of g1 are -1 turn of g2 and 4/3 turns of g3: g2's reference is back where it was.
  EXPECT_NEAR(g2(), -2 * kPi, 1e-12);
}

// A non-integer ratio after full turns: the coupling remembers the whole turns (a wrapped measure
// alone would see g2 half a turn off), in the solver's session and in the model between sessions.
TEST(Couplings, WholeTurnsSurviveNewSessions) {
  Model m = sample("three-gears.dcl");
  Turn g2(m, "g2");
  for (int round = 1; round <= 3; ++round) {
    Dragger drag(m, id(m, "g1"), tight());  // a new session each round, built from the model
    for (int k = 1; k <= 90; ++k) {
      const double t = 2 * kPi * (round - 1) + 2 * kPi * k / 90;
      ASSERT_TRUE(drag.move_to(turned(Vec3::Zero(), Vec3::UnitZ(), t)).converged);
      ASSERT_NEAR(g2(), -0.5 * t, 1e-12) << "round " << round << " step " << k;
    }
  }
  // After three turns of g1, g2 is half a turn round; a fresh solve leaves it there.
  std::vector<Pose> poses = m.poses();
  EXPECT_TRUE(solve(m, poses, tight()).converged);
  EXPECT_EQ(solve(m, poses, tight()).iterations, 0);
}

TEST(Couplings, PlanetarySetObeysWillis) {
  Model m = sample("planetary.dcl");
  const CheckResult c = check(m);
  EXPECT_EQ(c.dof, 2) << c.message;
  // The second and third planets' couplings repeat the first's equations (Willis again).
  EXPECT_EQ(c.redundant.size(), 2u) << c.message;

  // Ring free: whatever the solver makes of the two freedoms, Willis holds:
  // z_sun (w_sun - w_c) + z_ring (w_ring - w_c) = 0.
  {
    Model free = m;
    Dragger drag(free, id(free, "sun"), tight());
    Turn ring(free, "ring"), carrier(free, "carrier");
    double worst = 0;
    for (int k = 1; k <= 360; ++k) {
      const double t = 2 * kPi * k / 180;
      ASSERT_TRUE(drag.move_to(turned(Vec3::Zero(), Vec3::UnitZ(), t)).converged) << k;
      const double wc = carrier(), wr = ring();
      worst = std::max(worst, std::abs(20 * (t - wc) + 40 * (wr - wc)) / 20);
    }
    RecordProperty("willis_error_free_ring", sci(worst));
    EXPECT_LT(worst, 1e-12);
  }
  // Ring held: (w_sun - w_c) / (0 - w_c) = -40 / 20, so the carrier turns a third of the sun.
  Joint hold;
  hold.body2 = id(m, "ring");
  hold.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
  hold.twist = TwistSpec{Vec3::UnitX(), Vec3::UnitX(), 0, 0};
  m.add_joint(hold);
  EXPECT_EQ(check(m).dof, 1);
  Dragger drag(m, id(m, "sun"), tight());
  Turn carrier(m, "carrier"), ring(m, "ring"), planet(m, "planet1");
  double worst = 0;
  for (int k = 1; k <= 360; ++k) {
    const double t = 2 * kPi * k / 180;
    ASSERT_TRUE(drag.move_to(turned(Vec3::Zero(), Vec3::UnitZ(), t)).converged) << k;
    const double wc = carrier();
    worst = std::max(worst, std::abs((t - wc) / (ring() - wc) + 2.0) * std::abs(wc));
    planet();
  }
  RecordProperty("willis_error_ring_held", sci(worst));
  EXPECT_LT(worst, 1e-12);
  EXPECT_NEAR(carrier(), 4 * kPi / 3, 1e-12);
  // The planet turns relative to the carrier -2 times the sun's relative turn.
  EXPECT_NEAR(planet() - carrier(), -2 * (4 * kPi - 4 * kPi / 3), 1e-11);
}

TEST(Couplings, RackTravelsRadiusTimesThePinionsTurn) {
  Model m = sample("steering.dcl");
  const CheckResult c = check(m);
  EXPECT_EQ(c.dof, 1) << c.message;
  Dragger drag(m, id(m, "pinion"), tight());
  const Vec3 rack0 = m.body(id(m, "rack")).pose.x;
  const Vec3 knuckle0 = m.body(id(m, "knuckle_l")).pose.rotation_vector();
  double worst = 0;
  for (int k = 1; k <= 120; ++k) {
    const double t = 0.6 * std::sin(2 * kPi * k / 120);  // to 0.6, back through 0 to -0.6
    const SolveResult r = drag.move_to(turned(Vec3::Zero(), Vec3::UnitZ(), t));
    ASSERT_TRUE(r.converged) << k << " " << r.message;
    const Vec3 d = m.body(id(m, "rack")).pose.x - rack0;
    worst = std::max({worst, std::abs(d.x() - 0.3 * t), std::abs(d.y()), std::abs(d.z())});
    if (k == 30) {
      EXPECT_GT((m.body(id(m, "knuckle_l")).pose.rotation_vector() - knuckle0).norm(), 0.1);
    }
  }
  RecordProperty("rack_error", sci(worst));
  EXPECT_LT(worst, 1e-12);
}

TEST(Couplings, ScrewAdvancesItsPitchPerTurn) {
  Model m = sample("vice.dcl");
  const CheckResult c = check(m);
  EXPECT_EQ(c.dof, 1) << c.message;
  Dragger drag(m, id(m, "jaw"), tight());
  Turn screw(m, "screw", Vec3::UnitX());
  double worst = 0;
  for (int k = 1; k <= 80; ++k) {  // two pitches forward: two full turns
    const double x = 0.4 * k / 80;
    ASSERT_TRUE(drag.move_to(Pose{Quat::Identity(), Vec3(1 + x, 0, 0)}).converged) << k;
    worst = std::max(worst, std::abs(screw() - 2 * kPi * x / 0.2));
    worst = std::max(worst, std::abs(m.body(id(m, "screw")).pose.x.x() - x));
  }
  EXPECT_LT(worst, 1e-12);
  EXPECT_NEAR(screw(), 4 * kPi, 1e-12);

  // Left-handed: the same travel turns the screw the other way.
  std::string text =
      "object screw; end object jaw; position 1 0 0; end\n"
      "constraint object2 screw; hinge 0 0 0 0 0 0; axial 1 0 0; angle 1 0 0 1 0 0 "
      "max 0; screw 0 0 0 1 0 0 0 0 0 1 0 0 pitch 0.2 left; end\n"
      "constraint object2 jaw; hinge 1 0 0 0 0 0; axial 1 0 0; angle 0 0 1 0 0 1 "
      "max 0; twist 1 0 0 1 0 0; end\n"
      "constraint object1 screw; object2 jaw; hinge 1 0 0 0 0 0; angle 1 0 0 1 0 0 "
      "max 0; end\n";
  ParseResult r = parse_dcl(text);
  ASSERT_TRUE(r.ok()) << r.messages();
  Model left = std::move(*r.model);
  Dragger drag_left(left, id(left, "jaw"), tight());
  Turn screw_left(left, "screw", Vec3::UnitX());
  for (int k = 1; k <= 20; ++k) {
    ASSERT_TRUE(drag_left.move_to(Pose{Quat::Identity(), Vec3(1 + 0.1 * k / 20, 0, 0)}).converged);
    screw_left();
  }
  EXPECT_NEAR(screw_left(), -kPi, 1e-12);
}

// The jaw dragged exactly half a screw turn a step (0.1, the pitch 0.2): each step's target
// turns the screw by pi, where the wrapped turn's unwrapping next to the last seen is a tie (the
// short way round either way). Every step is made, the screw turned by 2 pi x / pitch (its
// rotation about x, compared as a rotation, so no unwrapping of the test's own) and travelled x,
// and the model's phase kept so that a fresh measure of its poses finds the coupling holding.
// Before, the third step (x = 0.30000000000000004, a hair past the half turn) failed out of
// reach 8.9e-8 from its target.
TEST(Couplings, ScrewDraggedHalfATurnAStepGetsThere) {
  for (const SolveOptions& o : {SolveOptions{}, tight()}) {
    SCOPED_TRACE(o.tolerance);
    Model m = sample("vice.dcl");
    Dragger drag(m, id(m, "jaw"), o);
    for (int k = 1; k <= 12; ++k) {  // four turns forward, then two back
      const double x = 0.1 * (k <= 8 ? k : 16 - k);
      const SolveResult r = drag.move_to(Pose{Quat::Identity(), Vec3(1 + x, 0, 0)});
      ASSERT_TRUE(r.converged) << k << " " << r.message;
      const Pose& screw = m.body(id(m, "screw")).pose;
      const Quat expected(Eigen::AngleAxisd(2 * kPi * x / 0.2, Vec3::UnitX()));
      EXPECT_LT(screw.q.angularDistance(expected), 1e-6) << k;
      EXPECT_NEAR(screw.x.x(), x, 1e-6) << k;
      EXPECT_LT((m.body(id(m, "jaw")).pose.x - Vec3(1 + x, 0, 0)).norm(), 1e-6) << k;
      // The model took the step's turn too: its coupling holds at its poses, measured afresh.
      for (const ConstraintReport& c : measure(m, m.poses(), o)) {
        EXPECT_TRUE(c.satisfied) << k << " joint " << c.joint.value << " " << c.residual;
      }
    }
  }
}

// The vice's jaw moved in one step by more than half a screw turn's travel (0.58 of a turn,
// pi + 0.5 rad, was as far as a held solve went: its Newton steps saw the screw's turn unwrapped
// next to the turn it began from, which flips a whole turn past half a turn, and it stalled
// there; the drag fell to the pull). The held solve a drag step begins with (StopWhenSlow) now
// makes it, 0.2 rad of the screw a step: the screw turned 2 pi x / pitch as a rotation, travelled
// x, the jaw at its target, and every joint holding measured afresh from the poses. Dragged back
// in one step too.
TEST(Couplings, HeldSolveTurnsAScrewMoreThanHalfATurnInOneStep) {
  for (const double x : {0.15, 0.3, 0.55, 1.0}) {
    SCOPED_TRACE(x);
    Model m = sample("vice.dcl");
    const BodyId jaw = id(m, "jaw"), screw = id(m, "screw");
    std::vector<bool> held(static_cast<size_t>(m.body_count()), false);
    held[static_cast<size_t>(jaw.value)] = true;
    Session session(m, SolveOptions{}, held, Session::Stuck::StopWhenSlow);
    for (const double to : {x, 0.0}) {
      std::vector<Pose> poses = m.poses();
      poses[static_cast<size_t>(jaw.value)] = Pose{Quat::Identity(), Vec3(1 + to, 0, 0)};
      const SolveResult r = session.solve(poses);
      ASSERT_TRUE(r.converged) << to << " " << r.message;
      EXPECT_FALSE(session.far());
      m.set_poses(poses);
      const Pose& p = m.body(screw).pose;
      const Quat expected(Eigen::AngleAxisd(2 * kPi * to / 0.2, Vec3::UnitX()));
      EXPECT_LT(p.q.angularDistance(expected), 1e-6) << to;
      EXPECT_NEAR(p.x.x(), to, 1e-6) << to;
      EXPECT_LT((m.body(jaw).pose.x - Vec3(1 + to, 0, 0)).norm(), 1e-9) << to;
      for (const ConstraintReport& c : measure(m, m.poses(), SolveOptions{})) {
        EXPECT_TRUE(c.satisfied) << to << " joint " << c.joint.value << " " << c.residual;
      }
    }
  }
}

// Poses read back after a solve that turned a coupling on by many turns (a held solve does: the
// test above): the turns read are the wrapped ones plus whole turns, and the equation holds with
// them. A screw of pitch 0.2 (f = s - pitch theta / 2 pi) advanced 1.03, 5.15 turns; a gear pair
// 0.1 theta0 + theta1 = 0 whose first gear turned 5 turns and 0.3 rad (the second 0.53 turn back):
// 4 whole turns either way were tried before, and neither read held.
TEST(Couplings, PosesReadBackTakeManyWholeTurns) {
  const double last[2] = {0, 0};
  CouplingMeasure screw;
  screw.angles = 1;
  screw.k[0] = -0.2 / (2 * kPi);
  screw.s = 1.03;
  screw.theta[0] = std::remainder(2 * kPi * 1.03 / 0.2, 2 * kPi);
  CouplingMeasure gears;
  gears.angles = 2;
  gears.k[0] = 0.1, gears.k[1] = 1;
  const double turned = 10 * kPi + 0.3;
  gears.theta[0] = std::remainder(turned, 2 * kPi);
  gears.theta[1] = std::remainder(-0.1 * turned, 2 * kPi);
  for (const CouplingMeasure& m : {screw, gears}) {
    double turns[2] = {0, 0};
    unwrap_read(m, last, 0, turns);
    double f = m.s;
    for (int i = 0; i < m.angles; ++i) {
      f += m.k[i] * turns[i];
      const double whole = (turns[i] - m.theta[i]) / (2 * kPi);
      EXPECT_NEAR(whole, std::round(whole), 1e-12) << i;
    }
    EXPECT_LT(std::abs(f), 1e-12) << m.angles;
  }
}

// Two gears on the frame (radii 1 and 2) each carry a crank; the cranks' ends are joined by two
// links: a closed loop through the gear mesh (a geared five-bar, one degree of freedom). The
// elbow follows the circle intersection on its branch through two full turns of the first gear.
TEST(Couplings, GearsInAClosedLoopWithALinkageDragWithoutAJump) {
  const char* text = R"(
object g1; end
object g2; position 3 0 0; end
object l1; position 0.8 0 0; rotation 0 0 0.8; end
object l2; position 4 0 0; rotation 0 0 2.3; end
constraint object2 g1; hinge 0 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object2 g2; hinge 3 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object1 g1; object2 g2; gear 0 0 0 0 0 1 0 0 0 0 0 1 ratio 0.5; end
constraint object1 g1; object2 l1; hinge 0.8 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object1 g2; object2 l2; hinge 1 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object1 l1; object2 l2; hinge 2.5 0 0 2.5 0 0; end
)";
  ParseResult r = parse_dcl(text);
  ASSERT_TRUE(r.ok()) << r.messages();
  Model m = std::move(*r.model);
  // The links start near the elbow-up branch, not joined: assembly puts them together.
  ASSERT_TRUE(assemble(m, tight()).converged);
  EXPECT_EQ(check(m).dof, 1);
  auto elbow = [&] { return m.body(id(m, "l1")).pose.apply(Vec3(2.5, 0, 0)); };
  auto pin1 = [&] { return m.body(id(m, "g1")).pose.apply(Vec3(0.8, 0, 0)); };
  auto pin2 = [&] { return m.body(id(m, "g2")).pose.apply(Vec3(1, 0, 0)); };
  auto side = [&] {  // which side of pin1 -> pin2 the elbow is on
    const Vec3 a = pin2() - pin1(), b = elbow() - pin1();
    return a.x() * b.y() - a.y() * b.x() > 0 ? 1.0 : -1.0;
  };
  const double branch = side();
  Dragger drag(m, id(m, "g1"), tight());
  Turn g1(m, "g1"), g2(m, "g2");
  double worst = 0, ratio = 0, largest_step = 0;
  Vec3 last = elbow();
  for (int k = 1; k <= 720; ++k) {
    const double t = 4 * kPi * k / 720;
    ASSERT_TRUE(drag.move_to(turned(Vec3::Zero(), Vec3::UnitZ(), t)).converged) << k;
    // The elbow: two circles of radius 2.5 about the pins, on the branch it started on.
    const Vec3 p = pin1(), q = pin2(), d = q - p;
    const double L = d.norm(), h = std::sqrt(2.5 * 2.5 - L * L / 4);
    const Vec3 expected = p + d / 2 + branch * h * Vec3(-d.y(), d.x(), 0) / L;
    worst = std::max(worst, (elbow() - expected).norm());
    ratio = std::max(ratio, std::abs(g2() + 0.5 * g1()));
    largest_step = std::max(largest_step, (elbow() - last).norm());
    last = elbow();
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(ratio, 1e-12);
  // One degree of the first gear moves the elbow at most about a pin's speed times the lever.
  EXPECT_LT(largest_step, 0.1);
}

// Three gears meshed in a triangle with ratios that disagree (g1 -> g3 directly at -1, through g2
// at +2): the loop locks. check counts no freedom and names a coupling whose removal frees it; a
// drag of g1 fails and names the couplings it could not hold.
TEST(Couplings, DisagreeingGearPathsLockAndAreNamed) {
  const char* text = R"(
object g1; end
object g2; position 3 0 0; end
object g3; position 1.5 2 0; end
constraint object2 g1; hinge 0 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object2 g2; hinge 3 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object2 g3; hinge 1.5 2 0 0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object1 g1; object2 g2; gear 0 0 0 0 0 1 0 0 0 0 0 1 ratio 2; end
constraint object1 g2; object2 g3; gear 0 0 0 0 0 1 0 0 0 0 0 1 ratio 1; end
constraint object1 g1; object2 g3; gear 0 0 0 0 0 1 0 0 0 0 0 1 ratio 1; end
)";
  ParseResult r = parse_dcl(text);
  ASSERT_TRUE(r.ok()) << r.messages();
  Model m = std::move(*r.model);
  const CheckResult c = check(m);
  EXPECT_EQ(c.dof, 0) << c.message;
  // Any of the three meshes closes the locking loop.
  ASSERT_EQ(c.locking.size(), 3u) << c.message;
  EXPECT_EQ(c.locking[0].value, 3);
  const DragResult d = drag(m, id(m, "g1"), turned(Vec3::Zero(), Vec3::UnitZ(), 0.5), 5, tight());
  EXPECT_FALSE(d.converged);
  EXPECT_NE(d.message.find("gear"), std::string::npos) << d.message;
}

// A gear at its turn's limit, meshed with another: the limit in contact takes the last freedom
// (check counts none), but the mesh does not lock the pair: away from the limit they turn. The
// fourth audit's wheel at its limit was said to be locked by its two meshes ("removing one of
// Wheel-Pinion, Pinion-Rack frees it"), which a designer would remove for nothing.
TEST(Couplings, AGearAtItsLimitIsHeldByTheLimitNotLockedByItsMesh) {
  const char* joints = R"(
object g2; position 3 0 0; end
constraint object2 g1; hinge 0 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; twist 1 0 0 1 0 0 min -0.5 max 0.5; end
constraint object2 g2; hinge 3 0 0 0 0 0; angle 0 0 1 0 0 1 max 0; end
constraint object1 g1; object2 g2; gear 0 0 0 0 0 1 0 0 0 0 0 1 ratio 2; end
)";
  for (const char* g1 : {"object g1; end", "object g1; rotation 0 0 0.5; end"}) {
    ParseResult r = parse_dcl(std::string(g1) + joints);
    ASSERT_TRUE(r.ok()) << r.messages();
    const CheckResult c = check(*r.model);
    const bool at_limit = std::string(g1).find("rotation") != std::string::npos;
    EXPECT_EQ(c.dof, at_limit ? 0 : 1) << c.message;
    EXPECT_EQ(c.limits_active.size(), at_limit ? 1u : 0u) << c.message;
    EXPECT_TRUE(c.locking.empty()) << c.message;
    EXPECT_EQ(c.message.find("locked"), std::string::npos) << c.message;
  }
}

}  // namespace
}  // namespace dispcon
