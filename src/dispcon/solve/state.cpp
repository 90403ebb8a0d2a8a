#include "dispcon/solve/state.hpp"

#include <algorithm>
#include <cmath>
#include <new>

#include "dispcon/parts/angle.hpp"
#include "dispcon/parts/circle.hpp"
#include "dispcon/parts/coupling.hpp"
#include "dispcon/parts/cylinder.hpp"
#include "dispcon/parts/point.hpp"
#include "dispcon/parts/point_to_point.hpp"
#include "dispcon/parts/polyline.hpp"
#include "dispcon/parts/ring.hpp"
#include "dispcon/parts/same_rotation.hpp"
#include "dispcon/parts/segment.hpp"
#include "dispcon/parts/sphere.hpp"
#include "dispcon/parts/twist.hpp"

namespace dispcon {

namespace {

Vec3 rotated(const Vec3& dR, const Vec3& v) {
  return quat_from_rotation_vector(dR) * v;
}

Frame frame(const BodyState& b) {
  return Frame{b.R, b.x, b.G};
}

}  // namespace

Nearest nearest_on_guide(const Vec3& p1, const Guide* guide, const Vec3& p, BoundTest bound) {
  if (!guide) return nearest_on_point(p1, p);
  const Guide& g = *guide;
  switch (g.kind) {
    case GuideKind::Point:
      return nearest_on_point(p1, p);
    case GuideKind::Axial:
      return nearest_on_segment(p1, g.dir, g.min, g.max, p, bound);
    case GuideKind::Planar:
      return nearest_on_ring(p1, g.dir, g.min, g.max, p, bound);
    case GuideKind::Sphere:
      return nearest_in_sphere(p1, g.min, g.max, p, bound);
    case GuideKind::Circle:
      return nearest_on_circle(p1, g.dir, g.radius, p);
    case GuideKind::Cylinder:
      return nearest_on_cylinder(p1, g.dir, g.radius, g.min, g.max, p, bound);
    case GuideKind::Polyline:
      return nearest_on_polyline(g.points, p, bound);
  }
  return nearest_on_point(p1, p);
}

void BodyState::set_pose(const Pose& pose) {
  // A unit quaternion is taken bit for bit (normalising it again may change its last bits), so
  // measuring the poses a solve returned gives the very residuals it reported.
  q = std::abs(pose.q.squaredNorm() - 1) <= 1e-15 ? pose.q : pose.q.normalized();
  x = pose.x;
  R = q.toRotationMatrix();
  G = R * c + x;
  if (physics) K = m * R * inertia_local->inverse() * R.transpose();
}

namespace {

// quat_from_rotation_vector for the turns of a Newton step, mostly under a hundredth of a
// radian: there the series of cos(a / 2) and sin(a / 2) / a to a^6 is exact to rounding (the
// next terms are below 1e-20) and needs neither the angle's square root nor sin and cos.
Quat small_turn(const Vec3& r) {
  const double a2 = r.squaredNorm();
  if (!(a2 < 1e-4)) return quat_from_rotation_vector(r);
  const double c = 1 - a2 / 8 * (1 - a2 / 48 * (1 - a2 / 120));
  const double s = 0.5 * (1 - a2 / 24 * (1 - a2 / 80 * (1 - a2 / 168)));
  return Quat(c, s * r.x(), s * r.y(), s * r.z());
}

}  // namespace

void BodyState::displace(const Vec3& dRot, const Vec3& dTrans) {
  q = (small_turn(dRot) * q).normalized();
  R = q.toRotationMatrix();
  G += dTrans;
  x = G - R * c;
  if (physics) K = m * R * inertia_local->inverse() * R.transpose();
}

SolverState::SolverState(const Model& model, const std::vector<Pose>& poses,
                         const SolveOptions& options, const std::vector<bool>& held) {
  const int nb = model.body_count();
  bodies.resize(static_cast<size_t>(nb));
  const std::vector<double> k = model.abilities_to_rotate();
  if (options.scheme == Scheme::Jacobi) {
    proposed_turn.resize(static_cast<size_t>(nb));
    proposed_move.resize(static_cast<size_t>(nb));
  }
  for (int i = 0; i < nb; ++i) {
    const Body& b = model.body(BodyId{i});
    BodyState& s = bodies[static_cast<size_t>(i)];
    s.c = b.center;
    s.movable = !b.fixed && !(i < static_cast<int>(held.size()) && held[static_cast<size_t>(i)]);
    s.physics = options.use_physics && b.has_physics();
    if (s.physics) {
      s.m = *b.mass;
      s.inv_m = 1 / s.m;
      s.inertia_local = &*b.inertia;
    } else {
      s.K = k[static_cast<size_t>(i)] * Mat3::Identity();
    }
    s.set_pose(poses.at(static_cast<size_t>(i)));
  }
  joints.resize(static_cast<size_t>(model.joint_count()));
  for (int c = 0; c < model.joint_count(); ++c) {
    const Joint& j = model.joint(JointId{c});
    JointState& js = joints[static_cast<size_t>(c)];
    js.joint = &j;
    js.b1 = j.body1.value;
    js.b2 = j.body2.value;
    js.active = j.active_at(options.time);
    js.bounded =
        (j.guide && j.guide->kind != GuideKind::Point && j.guide->kind != GuideKind::Circle) ||
        (j.angle && (j.angle->min > 0 || j.angle->max < kPi) && j.angle->min != j.angle->max) ||
        (j.twist && j.twist->min != j.twist->max);
    if (j.coupling) {
      // The phase holds at the model's poses: the turns there are the first ones seen.
      const Body& m1 = model.body(j.body1);
      const Body& m2 = model.body(j.body2);
      const CouplingMeasure m =
          measure_coupling(*j.coupling, Frame{m1.pose.rotation(), m1.pose.x, m1.world_center()},
                           Frame{m2.pose.rotation(), m2.pose.x, m2.world_center()}, false);
      js.phase = j.coupling->phase.value_or(0);
      js.last[0] = m.theta[0];
      js.last[1] = m.theta[1];
    }
    const BodyState& s1 = bodies[static_cast<size_t>(js.b1)];
    const BodyState& s2 = bodies[static_cast<size_t>(js.b2)];
    if (!s1.movable && !s2.movable) {
      js.mu1 = js.mu2 = 0;
    } else if (!s1.movable) {
      js.mu1 = 0, js.mu2 = 1;
    } else if (!s2.movable) {
      js.mu1 = 1, js.mu2 = 0;
    } else {
      js.mu1 = model.move_share(JointId{c});
      js.mu2 = 1 - js.mu1;
    }
    if (js.active) {
      if (s1.movable) ++bodies[static_cast<size_t>(js.b1)].n;
      if (s2.movable) ++bodies[static_cast<size_t>(js.b2)].n;
    }
  }
  // Seed 3.2: weight 1/max(n_i, n_j); a body that cannot move does not count (its n is moot).
  for (JointState& js : joints) {
    const BodyState& s1 = bodies[static_cast<size_t>(js.b1)];
    const BodyState& s2 = bodies[static_cast<size_t>(js.b2)];
    const int n = std::max(s1.movable ? s1.n : 0, s2.movable ? s2.n : 0);
    js.w = n == 0 ? 0 : options.seed_weights ? options.relaxation / n : options.relaxation;
  }
  unwrap_couplings();
}

// Each coupling's turns move on by the short way round from the last seen (near half a turn, the
// way its equation holds: unwrap_turns), and its phase by the whole turns the wrapped measure
// dropped, so the equation stays continuous through full turns.
void SolverState::unwrap_couplings() {
  for (JointState& js : joints) {
    if (!js.joint->coupling) continue;
    const CouplingMeasure m = coupling(js, false);
    double turns[2];
    unwrap_read(m, js.last, js.phase, turns);
    for (int i = 0; i < m.angles; ++i) {
      js.phase += m.k[i] * (m.theta[i] - turns[i]);
      js.last[i] = m.theta[i];
    }
  }
}

void SolverState::follow_couplings(const std::vector<int>& group_joints) {
  for (int c : group_joints) {
    JointState& js = joints[static_cast<size_t>(c)];
    if (!js.joint->coupling) continue;
    const CouplingMeasure m = coupling(js, false);
    double turns[2];
    unwrap_turns(m, js.last, js.phase, turns);
    for (int i = 0; i < m.angles; ++i) {
      js.phase += m.k[i] * (m.theta[i] - turns[i]);
      js.last[i] = m.theta[i];
    }
  }
}

CouplingMeasure SolverState::coupling(const JointState& js, bool with_rows) const {
  return measure_coupling(*js.joint->coupling, frame(bodies[static_cast<size_t>(js.b1)]),
                          frame(bodies[static_cast<size_t>(js.b2)]), with_rows);
}

void SolverState::write_poses(std::vector<Pose>& poses) const {
  poses.resize(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) poses[i] = bodies[i].pose();
}

void SolverState::read_poses(const std::vector<Pose>& poses) {
  for (size_t i = 0; i < bodies.size(); ++i) bodies[i].set_pose(poses[i]);
  unwrap_couplings();
}

Mobility SolverState::mobility(const JointState& js, int side) const {
  const BodyState& b = bodies[static_cast<size_t>(side == 1 ? js.b1 : js.b2)];
  Mobility m;
  m.G = b.G;
  m.mu = side == 1 ? js.mu1 : js.mu2;
  m.A = b.movable ? Mat3(m.mu * b.K) : Mat3::Zero();
  return m;
}

JointGeometry SolverState::geometry(const JointState& js, BoundTest bound) const {
  const Joint& j = *js.joint;
  const BodyState& s1 = bodies[static_cast<size_t>(js.b1)];
  const BodyState& s2 = bodies[static_cast<size_t>(js.b2)];
  JointGeometry g;
  if (j.has_translation()) {
    g.translation = true;
    g.P2 = s2.R * j.p2 + s2.x;
    if (!j.guide || j.guide->kind == GuideKind::Point) {
      // A point: its rows are the world's axes, which do not turn with body 1, so the Jacobian
      // of a chord step's factorisation stays nearer the current one.
      g.nearest = nearest_on_point(j.p1, j.p1);
      g.Q = s1.R * j.p1 + s1.x;
    } else {
      const Vec3 local = s1.R.transpose() * (g.P2 - s1.x);
      g.nearest = nearest_on_guide(j.p1, &*j.guide, local, bound);
      g.Q = s1.R * g.nearest.q + s1.x;
      for (int k = 0; k < g.nearest.rows; ++k) {
        Vec3& n = g.nearest.normals[static_cast<size_t>(k)];
        n = s1.R * n;
      }
    }
  }
  if (j.angle) {
    g.a1 = s1.R * j.angle->a1;
    g.a2 = s2.R * j.angle->a2;
  }
  if (j.twist) {
    g.b1 = s1.R * j.twist->b1;
    g.b2 = s2.R * j.twist->b2;
  }
  return g;
}

double SolverState::residual(const JointState& js) const {
  if (!js.active) return 0;
  return residual_at(js, geometry(js));
}

double SolverState::residual_at(const JointState& js, const JointGeometry& g) const {
  const Joint& j = *js.joint;
  double r = g.translation ? (g.P2 - g.Q).norm() : 0.0;
  if (j.angle) r = std::max(r, angle_violation(g.a1, g.a2, j.angle->min, j.angle->max));
  if (j.twist) {
    const double t = twist_angle(g.a1, g.a2, g.b1, g.b2);
    r = std::max(r, std::abs(twist_violation(t, j.twist->min, j.twist->max)));
  }
  if (j.coupling)
    r = std::max(r, std::abs(coupling_residual(coupling(js, false), js.last, js.phase)));
  if (j.same_rotation) {
    r = std::max(r, rotation_between(bodies[static_cast<size_t>(js.b1)].q,
                                     bodies[static_cast<size_t>(js.b2)].q)
                        .norm());
  }
  return r;
}

bool SolverState::at_limit(const JointState& js, double band) const {
  PartRows parts[kPartSlots];
  rows(js, BoundTest{band}, parts);
  return parts[0].at_limit || parts[1].at_limit || parts[2].at_limit;
}

void SolverState::rows(const JointState& js, const JointBounds& bounds, PartRows out[kPartSlots],
                       bool jacobian) const {
  rows_at(js, geometry(js, bounds.part(0)), bounds, out, jacobian);
}

double SolverState::residual_keeping(const JointState& js, JointGeometry& g) const {
  new (&g) JointGeometry(geometry(js));
  return js.active ? residual_at(js, g) : 0.0;
}

double SolverState::rows_and_residual(const JointState& js, BoundTest bound,
                                      PartRows out[kPartSlots], bool jacobian) const {
  if (!geometry_without_bounds(js)) {
    rows(js, bound, out, jacobian);  // the nearest point of a guide with ends depends on the band
    return residual(js);
  }
  const JointGeometry g = geometry(js);
  rows_at(js, g, JointBounds{bound}, out, jacobian);
  return js.active ? residual_at(js, g) : 0.0;
}

void SolverState::rows_at(const JointState& js, const JointGeometry& g, const JointBounds& bounds,
                          PartRows out[kPartSlots], bool jacobian) const {
  const Joint& j = *js.joint;
  for (int p = 0; p < kPartSlots; ++p) out[p].count = 0, out[p].at_limit = false;
  // Each part's rows are built where they go (placement new of the returned value, which C++17
  // builds in place): assigning it copied a PartRows of 324 bytes (rep movsq), about 5 % of a
  // drag step of the grid.
  if (g.translation) {
    new (&out[0]) PartRows(point_rows(g.Q, g.P2, bodies[static_cast<size_t>(js.b1)].G,
                                      bodies[static_cast<size_t>(js.b2)].G, g.nearest, jacobian));
  }
  if (j.angle) {
    new (&out[1])
        PartRows(angle_rows(g.a1, g.a2, j.angle->min, j.angle->max, bounds.part(1), jacobian));
  }
  if (j.twist) {
    new (&out[2]) PartRows(twist_rows(g.a1, g.a2, g.b1, g.b2, j.twist->min, j.twist->max,
                                      bounds.part(2), jacobian, j.angle->max > 0));
  }
  if (j.coupling) new (&out[3]) PartRows(coupling_rows(coupling(js, true), js.last, js.phase));
  // (In the angle's slot: a same rotation has none.)
  if (j.same_rotation) {
    new (&out[1]) PartRows(same_rotation_rows(bodies[static_cast<size_t>(js.b1)].q,
                                              bodies[static_cast<size_t>(js.b2)].q, jacobian));
  }
}

namespace {

// The way out of a guide's set at the bound the point p (object1's frame) rests on, as the
// guide's nearest point finds that bound with the same test (object1's frame); zero at none.
Vec3 guide_outward(const Guide& g, const Vec3& p1, const Vec3& p, BoundTest bound) {
  const Vec3 d = p - p1;
  switch (g.kind) {
    case GuideKind::Axial:
    case GuideKind::Cylinder: {
      const double lambda = d.dot(g.dir);
      if (bound.above(lambda, g.min, g.max)) return g.dir;
      if (bound.below(lambda, g.min, g.max)) return -g.dir;
      return Vec3::Zero();
    }
    case GuideKind::Planar:
    case GuideKind::Sphere: {
      const Vec3 across = g.kind == GuideKind::Planar ? Vec3(d - d.dot(g.dir) * g.dir) : d;
      const double r = across.norm();
      const Vec3 radial =
          unit_or(across, g.kind == GuideKind::Planar ? any_perpendicular(g.dir) : Vec3::UnitX());
      if (bound.above(r, g.min, g.max)) return radial;
      if (g.min > 0 && bound.below(r, g.min, g.max)) return -radial;
      return Vec3::Zero();
    }
    case GuideKind::Polyline: {
      const Nearest n = nearest_on_polyline(g.points, p, bound);
      if (!n.at_limit || g.points.size() < 2) return Vec3::Zero();
      const size_t last = g.points.size() - 1;
      return n.q == g.points.front() ? unit_or(g.points[0] - g.points[1], Vec3::UnitX())
                                     : unit_or(g.points[last] - g.points[last - 1], Vec3::UnitX());
    }
    case GuideKind::Point:
    case GuideKind::Circle:
      return Vec3::Zero();
  }
  return Vec3::Zero();
}

}  // namespace

void SolverState::outward(const JointState& js, const JointBounds& bounds,
                          double out[kPartSlots][3]) const {
  for (int p = 0; p < kPartSlots; ++p) out[p][0] = out[p][1] = out[p][2] = 0;
  const Joint& j = *js.joint;
  const JointGeometry g = geometry(js, bounds.part(0));
  const BodyState& s1 = bodies[static_cast<size_t>(js.b1)];
  if (g.translation && g.nearest.at_limit && j.guide) {
    const Vec3 local = s1.R.transpose() * (g.P2 - s1.x);
    const Vec3 way = s1.R * guide_outward(*j.guide, j.p1, local, bounds.part(0));
    for (int k = 0; k < g.nearest.rows; ++k) out[0][k] = g.nearest.normals[k].dot(way);
  }
  // An angle's or a twist's bound as their rows take it (angle.cpp, twist.cpp): the upper one
  // first.
  if (j.angle && j.angle->min != j.angle->max) {
    const BoundTest b = bounds.part(1);
    const double theta = angle_between(g.a1, g.a2);
    const double max = j.angle->max, min = j.angle->min;
    if (max < kPi && max > 1e-6 && theta >= max - b.band) {
      out[1][0] = 1;
    } else if (min > 1e-6 && min < kPi - 1e-6 && theta <= min + b.band) {
      out[1][0] = -1;
    }
  }
  if (j.twist && j.twist->min != j.twist->max) {
    const BoundTest b = bounds.part(2);
    const double twist = twist_angle(g.a1, g.a2, g.b1, g.b2);
    const double violation = twist_violation(twist, j.twist->min, j.twist->max);
    const bool upper = j.twist->max < kPi && twist >= j.twist->max - b.band;
    const bool lower = !upper && j.twist->min > -kPi && twist <= j.twist->min + b.band;
    if (upper || lower || violation != 0) {
      out[2][0] = upper || (!lower && violation > 0) ? 1 : -1;
    }
  }
}

// The rotations one joint proposes (seed 4.2.3 order): the translation part's eq. 18 first,
// then the angle part on the axes as they would be after those, then the twist part after both.
void SolverState::propose_rotations(const JointState& js, Vec3& dR1, Vec3& dR2) const {
  const Joint& j = *js.joint;
  const JointGeometry g = geometry(js);
  const Mobility m1 = mobility(js, 1);
  const Mobility m2 = mobility(js, 2);
  dR1.setZero();
  dR2.setZero();
  if (g.translation) point_rotations(g.Q, g.P2, m1, m2, dR1, dR2);
  if (j.angle) {
    angle_rotations(rotated(dR1, g.a1), rotated(dR2, g.a2), j.angle->min, j.angle->max, m1, m2, dR1,
                    dR2);
  }
  if (j.twist) {
    twist_rotations(rotated(dR1, g.a1), rotated(dR2, g.a2), rotated(dR1, g.b1), rotated(dR2, g.b2),
                    j.twist->min, j.twist->max, m1, m2, dR1, dR2);
  }
  if (j.same_rotation) {
    same_rotation_rotations(quat_from_rotation_vector(dR1) * bodies[static_cast<size_t>(js.b1)].q,
                            quat_from_rotation_vector(dR2) * bodies[static_cast<size_t>(js.b2)].q,
                            m1, m2, dR1, dR2);
  }
  // The coupling's impulse, rotation half (its translation half follows in propose_translations).
  if (j.coupling) {
    coupling_corrections(coupling(js, true), js.last, js.phase, m1, m2, &dR1, &dR2, nullptr,
                         nullptr);
  }
}

void SolverState::propose_translations(const JointState& js, Vec3& dx1, Vec3& dx2) const {
  dx1.setZero();
  dx2.setZero();
  if (js.joint->coupling) {
    coupling_corrections(coupling(js, true), js.last, js.phase, mobility(js, 1), mobility(js, 2),
                         nullptr, nullptr, &dx1, &dx2);
  }
  if (!js.joint->has_translation()) return;
  const JointGeometry g = geometry(js);
  point_translations(g.Q, g.P2, mobility(js, 1), mobility(js, 2), dx1, dx2);
}

}  // namespace dispcon
