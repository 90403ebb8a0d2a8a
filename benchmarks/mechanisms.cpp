#include "mechanisms.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "slvs_include.hpp"

namespace bench {

using dispcon::AngleSpec;
using dispcon::Body;
using dispcon::BodyId;
using dispcon::Joint;
using dispcon::Model;
using dispcon::Pose;
using dispcon::Vec3;

namespace {

void revolute(Model& m, BodyId b1, BodyId b2, const Vec3& p1, const Vec3& p2) {
  Joint j;
  j.body1 = b1;
  j.body2 = b2;
  j.has_hinge = true;
  j.p1 = p1;
  j.p2 = p2;
  j.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
  m.add_joint(j);
}

BodyId body(Model& m, const std::string& name, const Vec3& at, double angle, bool fixed = false) {
  Body b;
  b.name = name;
  b.pose = Pose::from(at, Vec3(0, 0, angle));
  b.fixed = fixed;
  return m.add_body(b);
}

}  // namespace

std::vector<FourBarProblem> fourbar_copies(int n, const FourBarProblem& p) {
  return std::vector<FourBarProblem>(static_cast<size_t>(std::max(0, n)), p);
}

std::vector<FourBarProblem> fourbar_variants(int n) {
  std::vector<FourBarProblem> out;
  // Fractional parts of k times irrational steps: well spread in [0, 1), never repeating.
  auto spread = [](int k, double step) { return std::fmod(0.5 + k * step, 1.0); };
  for (int k = 0; k < n; ++k) {
    FourBarProblem p;
    p.a *= 0.9 + 0.2 * spread(k, 0.6180339887498949);
    p.b *= 0.9 + 0.2 * spread(k, 0.4142135623730950);
    p.c *= 0.9 + 0.2 * spread(k, 0.7320508075688772);
    p.d *= 0.9 + 0.2 * spread(k, 0.2360679774997897);
    p.t += 0.3 * (2 * spread(k, 0.3166247903554) - 1);
    // Still a crank-rocker (the crank the shortest, s + l < p + q): a 10 % change leaves 4.4
    // against 4.95 at worst. The pin B where the coupler and rocker meet, on the branch above
    // the ground (the benchmark's), then the rough start off it as the benchmark's is (0.92 left,
    // 0.50 below).
    const double ax = p.a * std::cos(p.t), ay = p.a * std::sin(p.t);
    const double dx = p.d - ax, dy = -ay, l = std::hypot(dx, dy);
    const double along = (p.b * p.b - p.c * p.c + l * l) / (2 * l);
    const double h = std::sqrt(p.b * p.b - along * along);
    const double bx = ax + (along * dx - h * dy) / l, by = ay + (along * dy + h * dx) / l;
    p.bx = bx - (0.6 + 0.5 * spread(k, 0.5772156649015329));
    p.by = by - (0.3 + 0.4 * spread(k, 0.6931471805599453));
    out.push_back(p);
  }
  return out;
}

Model fourbars_dispcon(const std::vector<FourBarProblem>& problems) {
  Model m;
  const int n = static_cast<int>(problems.size());
  for (int k = 0; k < n; ++k) {
    const FourBarProblem& p = problems[static_cast<size_t>(k)];
    const double z = 10.0 * k;
    const std::string s = std::to_string(k);
    const Vec3 A(p.a * std::cos(p.t), p.a * std::sin(p.t), z);
    const Vec3 B(p.bx, p.by, z), D(p.d, 0, z);
    const BodyId crank = body(m, "crank" + s, Vec3(0, 0, z), p.t, true);
    const BodyId coupler = body(m, "coupler" + s, A, std::atan2(B.y() - A.y(), B.x() - A.x()));
    const BodyId rocker = body(m, "rocker" + s, D, std::atan2(B.y() - D.y(), B.x() - D.x()));
    revolute(m, crank, coupler, Vec3(p.a, 0, 0), Vec3::Zero());
    revolute(m, coupler, rocker, Vec3(p.b, 0, 0), Vec3(p.c, 0, 0));
    revolute(m, Model::kWorld, rocker, D, Vec3::Zero());
  }
  return m;
}

double rocker_angle_dispcon(const Model& m, int k) {
  const Vec3 x = m.body(*m.find("rocker" + std::to_string(k))).pose.q * Vec3::UnitX();
  return std::atan2(x.y(), x.x());
}

SlvsResult fourbars_slvs(const std::vector<FourBarProblem>& problems, bool crank_angle) {
  const int n = static_cast<int>(problems.size());
  // Group 1: the workplane and the fixed points; group 2: the crank tip A and the pin B.
  std::vector<Slvs_Param> param;
  std::vector<Slvs_Entity> entity;
  std::vector<Slvs_Constraint> constraint;
  Slvs_hParam hp = 1;
  Slvs_hEntity he = 1;
  Slvs_hConstraint hc = 1;
  const Slvs_hGroup g1 = 1, g2 = 2;
  // Workplane: origin (0,0,0), normal z.
  param.push_back(Slvs_MakeParam(hp++, g1, 0));
  param.push_back(Slvs_MakeParam(hp++, g1, 0));
  param.push_back(Slvs_MakeParam(hp++, g1, 0));
  const Slvs_hEntity origin = he++;
  entity.push_back(Slvs_MakePoint3d(origin, g1, 1, 2, 3));
  param.push_back(Slvs_MakeParam(hp++, g1, 1));
  param.push_back(Slvs_MakeParam(hp++, g1, 0));
  param.push_back(Slvs_MakeParam(hp++, g1, 0));
  param.push_back(Slvs_MakeParam(hp++, g1, 0));
  const Slvs_hEntity normal = he++;
  entity.push_back(Slvs_MakeNormal3d(normal, g1, 4, 5, 6, 7));
  const Slvs_hEntity wp = he++;
  entity.push_back(Slvs_MakeWorkplane(wp, g1, origin, normal));
  auto point = [&](Slvs_hGroup g, double x, double y) {
    const Slvs_hParam u = hp++, v = hp++;
    param.push_back(Slvs_MakeParam(u, g, x));
    param.push_back(Slvs_MakeParam(v, g, y));
    const Slvs_hEntity h = he++;
    entity.push_back(Slvs_MakePoint2d(h, g, wp, u, v));
    return h;
  };
  std::vector<Slvs_hParam> b_params;
  for (int k = 0; k < n; ++k) {
    // Copies side by side in the plane (the problems are independent).
    const double ox = 10.0 * k;
    const FourBarProblem& p = problems[static_cast<size_t>(k)];
    const Slvs_hEntity O = point(g1, ox, 0);
    const Slvs_hEntity D = point(g1, ox + p.d, 0);
    const Slvs_hEntity far = point(g1, ox + 10 * std::cos(p.t), 10 * std::sin(p.t));
    const Slvs_hEntity line = he++;
    entity.push_back(Slvs_MakeLineSegment(line, g1, wp, O, far));
    const Slvs_hEntity A = point(g2, ox + p.a * std::cos(p.t) + 0.1, p.a * std::sin(p.t) - 0.1);
    b_params.push_back(hp);
    const Slvs_hEntity B = point(g2, ox + p.bx, p.by);
    auto distance = [&](Slvs_hEntity a, Slvs_hEntity b, double l) {
      constraint.push_back(Slvs_MakeConstraint(hc++, g2, SLVS_C_PT_PT_DISTANCE, wp, l, a, b, 0, 0));
    };
    distance(O, A, p.a);
    if (crank_angle) {
      // The crank O-A held at angle t to the ground O-D, as a sketch's dimension poses it.
      const Slvs_hEntity ground = he++;
      entity.push_back(Slvs_MakeLineSegment(ground, g1, wp, O, D));
      const Slvs_hEntity crank = he++;
      entity.push_back(Slvs_MakeLineSegment(crank, g2, wp, O, A));
      constraint.push_back(
          Slvs_MakeConstraint(hc++, g2, SLVS_C_ANGLE, wp, p.t * 180 / M_PI, 0, 0, ground, crank));
    } else {
      constraint.push_back(Slvs_MakeConstraint(hc++, g2, SLVS_C_PT_ON_LINE, wp, 0, A, 0, line, 0));
    }
    distance(A, B, p.b);
    distance(B, D, p.c);
  }
  SlvsResult out;
  out.result = solve_slvs(param, entity, constraint, g2);
  for (int k = 0; k < n; ++k) {
    const double bx = param[b_params[static_cast<size_t>(k)] - 1].val - 10.0 * k;
    const double by = param[b_params[static_cast<size_t>(k)]].val;
    out.rocker.push_back(std::atan2(by, bx - problems[static_cast<size_t>(k)].d));
  }
  return out;
}

Model closed_chain(int n) {
  Model m;
  const double R = n / (2 * M_PI), L = 2 * R * std::sin(M_PI / n);
  std::vector<BodyId> ids;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    const Vec3 at(R * std::cos(a) + 0.01 * std::sin(7.0 * i),
                  R * std::sin(a) + 0.01 * std::cos(3.0 * i), 0.01);
    ids.push_back(body(m, "l" + std::to_string(i), at, a + M_PI / 2 + M_PI / n, i == 0));
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

Model fourbar_grid(int rows, int cols) {
  // Nodes on a lattice; every lattice edge is a link hinged at both ends to the nodes' pins,
  // every cell a four-bar loop; the bottom row of nodes is fixed to the world. Links are bodies,
  // pins are point-to-point joints with angle about z (revolutes).
  Model m;
  auto node = [&](int r, int c) {
    return Vec3(1.0 * c + 0.05 * std::sin(3.0 * r + c), 1.0 * r + 0.05 * std::cos(r + 2.0 * c), 0);
  };
  std::vector<std::vector<BodyId>> pin_body(
      static_cast<size_t>(rows + 1),
      std::vector<BodyId>(static_cast<size_t>(cols + 1), Model::kWorld));
  std::vector<std::vector<Vec3>> pin_local(static_cast<size_t>(rows + 1),
                                           std::vector<Vec3>(static_cast<size_t>(cols + 1)));
  for (int c = 0; c <= cols; ++c) pin_local[0][static_cast<size_t>(c)] = Vec3(c, 0, 0);
  int count = 0;
  auto link = [&](int r0, int c0, int r1, int c1) {
    const Vec3 a = node(r0, c0), b = node(r1, c1);
    const BodyId id =
        body(m, "k" + std::to_string(count++), a, std::atan2(b.y() - a.y(), b.x() - a.x()));
    auto& pb = pin_body[static_cast<size_t>(r0)][static_cast<size_t>(c0)];
    if (r0 == 0 || pb != Model::kWorld) {
      revolute(m, pb, id, pin_local[static_cast<size_t>(r0)][static_cast<size_t>(c0)],
               Vec3::Zero());
    } else {
      pb = id;
      pin_local[static_cast<size_t>(r0)][static_cast<size_t>(c0)] = Vec3::Zero();
    }
    auto& qb = pin_body[static_cast<size_t>(r1)][static_cast<size_t>(c1)];
    if (qb != Model::kWorld) {
      revolute(m, qb, id, pin_local[static_cast<size_t>(r1)][static_cast<size_t>(c1)],
               Vec3(1, 0, 0));
    } else {
      qb = id;
      pin_local[static_cast<size_t>(r1)][static_cast<size_t>(c1)] = Vec3(1, 0, 0);
    }
  };
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c <= cols; ++c) link(r, c, r + 1, c);         // verticals
    for (int c = 0; c < cols; ++c) link(r + 1, c, r + 1, c + 1);  // horizontals above
  }
  return m;
}

Model crank_chain(int cranks) {
  Model m;
  const double pitch = 1.5, length = 1.0, turn = M_PI / 3;
  // A part of the chain: its centre midway along it, 0.05 above its pins' plane (the solids').
  auto part = [&](const std::string& name, const Vec3& at, double angle, double along,
                  bool fixed = false) {
    Body b;
    b.name = name;
    b.pose = Pose::from(at, Vec3(0, 0, angle));
    b.center = Vec3(0.5 * along, 0, 0.05);
    b.fixed = fixed;
    return m.add_body(b);
  };
  const BodyId ground = part("ground", Vec3::Zero(), 0, pitch * (cranks - 1), true);
  const Vec3 tip(length * std::cos(turn), length * std::sin(turn), 0);
  std::vector<BodyId> cs;
  for (int k = 0; k < cranks; ++k) {
    const Vec3 pin(k * pitch, 0, 0.1);
    cs.push_back(part("crank" + std::to_string(k), pin, turn, length));
    revolute(m, ground, cs.back(), pin, Vec3::Zero());
  }
  for (int k = 0; k + 1 < cranks; ++k) {
    const double layer = 0.1 * (k % 2);
    const BodyId c =
        part("coupler" + std::to_string(k), Vec3(k * pitch, 0, 0.2 + layer) + tip, 0, pitch);
    revolute(m, cs[static_cast<size_t>(k)], c, Vec3(length, 0, 0.1 + layer), Vec3::Zero());
    revolute(m, cs[static_cast<size_t>(k) + 1], c, Vec3(length, 0, 0.1 + layer), Vec3(pitch, 0, 0));
  }
  return m;
}

Model gear_train(int n) {
  Model m;
  auto radius = [](int i) { return i % 2 ? 0.5 : 1.0; };
  double x = 0;
  BodyId last{};
  for (int i = 0; i < n; ++i) {
    if (i > 0) x += radius(i - 1) + radius(i);
    const BodyId g = body(m, "g" + std::to_string(i), Vec3(x, 0, 0), 0);
    Joint axle;
    axle.body2 = g;
    axle.has_hinge = true;
    axle.p1 = Vec3(x, 0, 0);
    axle.angle = AngleSpec{Vec3::UnitZ(), Vec3::UnitZ(), 0, 0};
    m.add_joint(axle);
    if (i > 0) {
      Joint mesh;
      mesh.body1 = last;
      mesh.body2 = g;
      dispcon::CouplingSpec c;
      c.kind = dispcon::CouplingKind::Gear;
      c.value = radius(i - 1) / radius(i);
      mesh.coupling = c;
      m.add_joint(mesh);
    }
    last = g;
  }
  return m;
}

}  // namespace bench
