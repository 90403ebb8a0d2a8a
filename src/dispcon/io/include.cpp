#include "dispcon/io/include.hpp"

#include <cmath>
#include <stdexcept>

#include "dispcon/model/joint_kinds.hpp"
#include "dispcon/parts/coupling.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {

namespace {

Pose compose(const Pose& a, const Pose& b) {
  return Pose{(a.q * b.q).normalized(), a.apply(b.x)};
}

Pose inverse(const Pose& p) {
  const Quat q = p.q.conjugate();
  return Pose{q, -(q * p.x)};
}

// The side `side` (1 or 2) of every component of `j` carried into another frame by T: its points
// p -> T p, its vectors v -> T v (the arguments' sides are the rows' of components()).
void carry(Joint& j, int side, const Pose& T) {
  for (const ComponentRow& row : components()) {
    if (!has_component(j, row.id)) continue;
    ComponentValues v = get_component(j, row.id);
    size_t vector = 0;
    for (const ArgSpec& a : row.args) {
      const bool mine = a.side == side;
      if (a.kind == Arg::Point && mine) v.vectors[vector] = T.apply(v.vectors[vector]);
      if (a.kind == Arg::Direction && mine) v.vectors[vector] = T.q * v.vectors[vector];
      if (a.kind == Arg::Points && mine)
        for (Vec3& p : v.points) p = T.apply(p);
      vector += a.kind == Arg::Point || a.kind == Arg::Direction;
    }
    set_component(j, row.id, v);
  }
}

Frame frame(const Pose& pose, const Vec3& center) {
  return Frame{pose.rotation(), pose.x, pose.apply(center)};
}

// The coupling's turns measured between the bodies at (a1, a2) before the change of frame and at
// (b1, b2) after: its phase moves by the difference, so its equation holds where it held.
void shift_phase(const CouplingSpec& was, CouplingSpec& is, const Frame& a1, const Frame& a2,
                 const Frame& b1, const Frame& b2) {
  const CouplingMeasure before = measure_coupling(was, a1, a2, false);
  const CouplingMeasure after = measure_coupling(is, b1, b2, false);
  if (!before.valid || !after.valid) return;
  double shift = after.s - before.s;
  for (int i = 0; i < after.angles; ++i)
    shift += after.k[i] * std::remainder(after.theta[i] - before.theta[i], 2 * kPi);
  is.phase = was.phase.value_or(0) + shift;
}

// One body welded from all of `sub`'s, in the frame of its world: mass and inertia added up
// about the common centre (parallel axes) when every body has them, else the mean of the
// centres; fixed when one of them is.
Body welded(const Model& sub, const std::string& name) {
  Body out;
  out.name = name;
  bool physics = true;
  double mass = 0;
  Vec3 sum = Vec3::Zero();
  for (int i = 1; i < sub.body_count(); ++i) {
    const Body& b = sub.body(BodyId{i});
    out.fixed = out.fixed || b.fixed;
    physics = physics && b.has_physics();
    const double m = b.has_physics() ? *b.mass : 1.0;
    mass += m;
    sum += m * b.world_center();
  }
  out.center = sum / mass;
  if (!physics) return out;
  Mat3 J = Mat3::Zero();
  for (int i = 1; i < sub.body_count(); ++i) {
    const Body& b = sub.body(BodyId{i});
    const Mat3 R = b.pose.rotation();
    const Vec3 d = b.world_center() - out.center;
    J += R * *b.inertia * R.transpose() +
         *b.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  out.mass = mass;
  out.inertia = 0.5 * (J + J.transpose());
  return out;
}

}  // namespace

void include_model(Model& model, const Model& sub, const Inclusion& inc) {
  if (sub.body_count() < 2) throw std::invalid_argument("the included model has no object");
  const Pose& P = inc.placement;
  const Pose T = compose(inverse(model.body(inc.on).pose), P);  // sub-world -> on's frame
  Model solved = sub;
  if (inc.rigid) {
    const SolveResult r = assemble(solved);
    if (!r.converged)
      throw std::invalid_argument("the included model does not assemble (" + r.message + ")");
  }
  // Where each body of the sub-model went, and its pose in the frame it went into.
  std::vector<BodyId> into(static_cast<size_t>(solved.body_count()), inc.on);
  std::vector<Pose> local(static_cast<size_t>(solved.body_count()));
  if (inc.rigid) {
    Body b = welded(solved, inc.name);
    b.pose = P;
    b.line = inc.line;
    const BodyId id = model.add_body(b);
    for (int i = 1; i < solved.body_count(); ++i) {
      into[static_cast<size_t>(i)] = id;
      local[static_cast<size_t>(i)] = solved.body(BodyId{i}).pose;
    }
  } else {
    for (int i = 1; i < solved.body_count(); ++i) {
      Body b = solved.body(BodyId{i});
      b.name = inc.name + "." + b.name;
      b.pose = compose(P, b.pose);
      b.velocity = P.q * b.velocity;
      b.spin = P.q * b.spin;
      b.force = P.q * b.force;
      b.torque = P.q * b.torque;
      b.line = inc.line;
      into[static_cast<size_t>(i)] = model.add_body(b);
    }
  }
  for (const Joint& j : solved.joints()) {
    const size_t i1 = static_cast<size_t>(j.body1.value), i2 = static_cast<size_t>(j.body2.value);
    const bool world1 = j.body1 == Model::kWorld, world2 = j.body2 == Model::kWorld;
    // Inside a rigid body: it holds by construction.
    if (inc.rigid && !world1 && !world2) continue;
    Joint k = j;
    if (world1) carry(k, 1, T);
    if (world2) carry(k, 2, T);
    if (inc.rigid) carry(k, world1 ? 2 : 1, local[world1 ? i2 : i1]);
    k.body1 = into[i1];
    k.body2 = into[i2];
    k.line = inc.line;
    if (k.coupling) {
      const Body& s1 = solved.body(j.body1);
      const Body& s2 = solved.body(j.body2);
      const Body& m1 = model.body(k.body1);
      const Body& m2 = model.body(k.body2);
      shift_phase(*j.coupling, *k.coupling, frame(s1.pose, s1.center), frame(s2.pose, s2.center),
                  frame(m1.pose, m1.center), frame(m2.pose, m2.center));
    }
    model.add_joint(k);
  }
}

}  // namespace dispcon
