// The physics variant (seed 2.2) against mechanics: a pendulum's period, momentum of free systems,
// energy drift, the flying snake's order of events.
#include "dispcon/solve/dynamics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "support/samples.hpp"

namespace dispcon {
namespace {

// A compound pendulum hinged at the world's origin about z, its centre of mass d below the pivot.
struct Pendulum {
  double m = 2, Ic = 0.05, d = 1, g = 9.81;
  Model model;
  BodyId bob;
  explicit Pendulum(double start_angle) {
    Body b;
    b.name = "bob";
    b.mass = m;
    b.inertia = Mat3::Identity() * Ic;
    b.center = Vec3(0, -d, 0);
    b.pose = Pose::from(Vec3::Zero(), Vec3(0, 0, start_angle));
    bob = model.add_body(b);
    Joint j;
    j.body2 = bob;
    j.has_hinge = true;
    j.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
    model.add_joint(j);
  }
  double angle(const Pose& p) const { return p.rotation_vector().z(); }
  double energy(const Model& at) const {
    const Body& b = at.body(bob);
    const double w = b.spin.z();
    const double height = b.world_center().y();
    return 0.5 * (Ic + m * d * d) * w * w + m * g * height;
  }
};

AnimateOptions gravity(double duration, double dt) {
  AnimateOptions o;
  o.duration = duration;
  o.dt = dt;
  o.gravity = Vec3(0, -9.81, 0);
  o.solve.tolerance = 1e-12;
  return o;
}

TEST(Dynamics, PendulumSmallSwingPeriod) {
  Pendulum p(0.05);
  const double expected = 2 * kPi * std::sqrt((p.Ic + p.m * p.d * p.d) / (p.m * p.g * p.d));
  const AnimateResult r = animate(p.model, gravity(4 * expected, 1e-3));
  ASSERT_TRUE(r.converged) << r.message;
  // Downward zero crossings of the angle, interpolated.
  std::vector<double> crossings;
  for (size_t k = 1; k < r.frames.size(); ++k) {
    const double a0 = p.angle(r.frames[k - 1].poses[1]), a1 = p.angle(r.frames[k].poses[1]);
    if (a0 > 0 && a1 <= 0) {
      const double t0 = r.frames[k - 1].time, t1 = r.frames[k].time;
      crossings.push_back(t0 + (t1 - t0) * a0 / (a0 - a1));
    }
  }
  ASSERT_GE(crossings.size(), 3u);
  const double period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  RecordProperty("period_error_percent", std::to_string(100 * (period / expected - 1)));
  EXPECT_NEAR(period / expected, 1.0, 0.005) << "period " << period << " expected " << expected;
}

TEST(Dynamics, ConservativeSystemEnergyDrift) {
  Pendulum p(0.3);
  Model start = p.model;
  const double e0 = p.energy(start);
  const AnimateResult r = animate(p.model, gravity(2.0, 1e-3));
  ASSERT_TRUE(r.converged);
  const double drift = std::abs(p.energy(p.model) - e0) / std::abs(p.m * p.g * p.d) / 2.0;
  RecordProperty("energy_drift_per_second", std::to_string(drift));
  EXPECT_LT(drift, 0.01);  // under 1 % of m g d per second
}

TEST(Dynamics, FreeSystemKeepsItsMomentum) {
  // Two bars hinged together, spinning and drifting: no gravity, nothing fixed.
  Model m;
  Body a;
  a.name = "a";
  a.mass = 1.5;
  Mat3 Ja;
  Ja << 0.1, 0.01, 0, 0.01, 0.3, 0.02, 0, 0.02, 0.25;
  a.inertia = Ja;
  a.center = Vec3(0.5, 0, 0);
  a.velocity = Vec3(0.3, -0.2, 0.1);
  a.spin = Vec3(0.5, 1.0, -2.0);
  Body b = a;
  b.name = "b";
  b.mass = 0.7;
  b.pose.x = Vec3(1, 0, 0);
  b.velocity = Vec3(-0.1, 0.4, 0);
  b.spin = Vec3(0, -1.5, 1.0);
  const BodyId ia = m.add_body(a), ib = m.add_body(b);
  Joint j;
  j.body1 = ia;
  j.body2 = ib;
  j.has_hinge = true;
  j.p1 = Vec3(1, 0, 0);
  m.add_joint(j);
  auto momenta = [&](const Model& at, Vec3& P, Vec3& L) {
    P.setZero();
    L.setZero();
    for (int i = 1; i < at.body_count(); ++i) {
      const Body& x = at.body(BodyId{i});
      const Mat3 R = x.pose.rotation();
      P += *x.mass * x.velocity;
      L += R * *x.inertia * R.transpose() * x.spin + x.world_center().cross(*x.mass * x.velocity);
    }
  };
  AnimateOptions o;
  o.duration = 1.0;
  o.dt = 1e-3;
  o.solve.tolerance = 1e-12;
  // The start speeds do not respect the hinge: let the first frame project them, then measure.
  AnimateOptions first = o;
  first.duration = o.dt;
  ASSERT_TRUE(animate(m, first).converged);
  Vec3 P0, L0, P1, L1;
  momenta(m, P0, L0);
  const AnimateResult r = animate(m, o);
  ASSERT_TRUE(r.converged) << r.message;
  momenta(m, P1, L1);
  RecordProperty("linear_momentum_change", std::to_string((P1 - P0).norm()));
  RecordProperty("angular_momentum_change_relative", std::to_string((L1 - L0).norm() / L0.norm()));
  EXPECT_LT((P1 - P0).norm(), 1e-9 * (1 + P0.norm()));
  EXPECT_LT((L1 - L0).norm(), 0.02 * L0.norm());  // the stated bound: 2 % over 1 s at dt = 1 ms
}

TEST(Dynamics, FlyingSnakeSlidesHitsTheBoundAndSwingsBack) {
  Model m = test_support::sample("snake.dcl");
  const BodyId tail = *m.find("tail");
  AnimateOptions o = gravity(3.0, 0.005);
  o.solve.tolerance = 1e-9;
  const AnimateResult r = animate(m, o);
  ASSERT_TRUE(r.converged) << r.message;
  double hit = -1, back = -1, highest = -10;
  double start_x = r.frames.front().poses[static_cast<size_t>(tail.value)].x.x();
  bool slid_right_first = false;
  for (const Frame& f : r.frames) {
    const double x = f.poses[static_cast<size_t>(tail.value)].x.x();
    highest = std::max(highest, x);
    if (hit < 0 && x > start_x + 0.05) slid_right_first = true;
    if (hit < 0 && x >= 1 - 1e-6) hit = f.time;
    if (hit >= 0 && back < 0 && x < 0.5) back = f.time;
  }
  RecordProperty("bound_hit_time", std::to_string(hit));
  RecordProperty("slide_back_time", std::to_string(back));
  EXPECT_TRUE(slid_right_first);
  EXPECT_GT(hit, 0) << "the tail never reached the bound";
  EXPECT_GT(back, hit) << "the tail did not slide back";
  EXPECT_LE(highest, 1 + 1e-8);  // never beyond the bound
}

TEST(Dynamics, IterationCapWarnsNamesTheJointAndStopsWhenAsked) {
  // From t = 0.05 a second pivot, elsewhere, is demanded: impossible.
  for (bool stop : {false, true}) {
    Pendulum p(0.3);
    Joint j;
    j.body2 = p.bob;
    j.has_hinge = true;
    j.p1 = Vec3(0.5, 0, 0);
    j.t0 = 0.05;
    j.line = 42;
    p.model.add_joint(j);
    AnimateOptions o = gravity(0.1, 0.01);
    o.solve.max_iterations = 50;
    o.stop_on_violation = stop;
    const AnimateResult r = animate(p.model, o);
    EXPECT_FALSE(r.converged);
    ASSERT_FALSE(r.warnings.empty());
    EXPECT_NE(r.warnings.front().find("joint 1 (line 42"), std::string::npos) << r.warnings.front();
    ASSERT_GE(r.frames.size(), 6u);
    EXPECT_TRUE(r.frames[4].converged);   // t = 0.04
    EXPECT_FALSE(r.frames[5].converged);  // t = 0.05: the joint is active from here
    EXPECT_EQ(r.stopped, stop);
    EXPECT_EQ(r.frames.size(), stop ? 6u : 11u);
  }
}

}  // namespace
}  // namespace dispcon
