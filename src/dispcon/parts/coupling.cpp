#include "dispcon/parts/coupling.hpp"

#include <algorithm>
#include <cmath>

#include "dispcon/parts/gear.hpp"
#include "dispcon/parts/rack_pinion.hpp"
#include "dispcon/parts/screw.hpp"

namespace dispcon {

bool turn(const Vec3& n, const Vec3& r, const Vec3& ref, const Eigen::Matrix<double, 3, 12>* dref,
          int side, double& theta, Row* row) {
  const Vec3 m = n.cross(r);
  const double x = ref.dot(r);
  const double y = ref.dot(m);
  const double rr = x * x + y * y;
  if (!(rr > 1e-24 * std::max(1.0, ref.squaredNorm()))) return false;
  theta = -std::atan2(y, x);
  if (!row) return true;
  // d theta = -(x dy - y dx) / (x^2 + y^2), with dx = dR . (r x ref) + r . dref and
  // dy = dR . (m x ref) + m . dref (r and m turn with the body, dR its rotation).
  row->setZero();
  row->segment<3>(side) = -(x * m.cross(ref) - y * r.cross(ref)).transpose() / rr;
  if (dref) *row -= (x * m - y * r).transpose() * *dref / rr;
  return true;
}

CouplingMeasure measure_coupling(const CouplingSpec& c, const Frame& f1, const Frame& f2,
                                 bool with_rows) {
  switch (c.kind) {
    case CouplingKind::Gear:
    case CouplingKind::Belt:
      return measure_gear(c, f1, f2, with_rows);
    case CouplingKind::Rack:
      return measure_rack_pinion(c, f1, f2, with_rows);
    case CouplingKind::Screw:
      return measure_screw(c, f1, f2, with_rows);
  }
  return {};
}

double unwrap(double theta, double last) {
  return last + std::remainder(theta - last, 2 * kPi);
}

namespace {
// How near half a turn from the last seen a turn is taken the way round its equation holds
// (radians): wider than the relative turn of a Newton step (two bodies at the seed's 0.2 rad)
// so that a solve's steps about the half turn all see the same way round.
constexpr double kNearHalfTurn = 0.5;
}  // namespace

void unwrap_turns(const CouplingMeasure& m, const double last[2], double phase, double turns[2]) {
  double f = m.s - phase;
  for (int i = 0; i < m.angles; ++i) {
    turns[i] = unwrap(m.theta[i], last[i]);
    f += m.k[i] * turns[i];
  }
  for (int i = 0; i < m.angles; ++i) {
    const double from = turns[i] - last[i];
    if (!(std::abs(from) > kPi - kNearHalfTurn)) continue;
    // The other way round: a whole turn less (or more), f by k 2 pi.
    const double other = from > 0 ? -2 * kPi : 2 * kPi;
    const double g = f + m.k[i] * other;
    if (std::abs(g) < std::abs(f)) turns[i] += other, f = g;
  }
}

void unwrap_read(const CouplingMeasure& m, const double last[2], double phase, double turns[2],
                 bool held_before) {
  unwrap_turns(m, last, phase, turns);
  if (!m.valid || !held_before) return;
  bool moved = false;
  double f = m.s - phase, turn = 0;
  for (int i = 0; i < m.angles; ++i) {
    moved = moved || m.theta[i] != last[i];
    f += m.k[i] * turns[i];
    turn = std::max(turn, std::abs(2 * kPi * m.k[i]));
  }
  // f within a millionth of the largest turn's travel: held.
  const double held = 1e-6 * turn;
  if (!moved || !(std::abs(f) > held)) return;
  // The whole turns that make f hold, the fewest first. The phase takes only their sum
  // k . 2 pi n, so any that hold will do. A held solve turns a screw or a gear on as far as its
  // steps go (a jaw moved 1 in one step: its screw 5 turns; a gear's mate at a ratio of 10 turned
  // half a turn: 5 turns), so each turn's count is had at once from the others' (a few either
  // way).
  constexpr int kTurns = 4;
  double best[2] = {0, 0};
  double fewest = -1;
  auto consider = [&](double n0, double n1) {
    if (!(std::abs(n0) < 1e9 && std::abs(n1) < 1e9)) return;
    const double g = f + 2 * kPi * (m.k[0] * n0 + (m.angles == 2 ? m.k[1] * n1 : 0));
    const double count = std::abs(n0) + std::abs(n1);
    if (std::abs(g) <= held && (fewest < 0 || count < fewest)) {
      best[0] = n0, best[1] = n1, fewest = count;
    }
  };
  // The count of turn i that makes f hold with the other's count `other`.
  auto solve = [&](int i, double other) {
    if (m.k[i] == 0) return 0.0;
    const double rest = m.angles == 2 ? f + 2 * kPi * m.k[1 - i] * other : f;
    return std::round(-rest / (2 * kPi * m.k[i]));
  };
  if (m.angles == 1) {
    consider(solve(0, 0), 0);
  } else {
    for (int n = -kTurns; n <= kTurns; ++n) {
      consider(n, solve(1, n));
      consider(solve(0, n), n);
    }
  }
  if (fewest < 0) return;
  for (int i = 0; i < m.angles; ++i) turns[i] += 2 * kPi * best[i];
}

bool coupling_held(const CouplingMeasure& m, double phase) {
  if (!m.valid) return false;
  double f = m.s - phase, turn = 0;
  for (int i = 0; i < m.angles; ++i) {
    f += m.k[i] * m.theta[i];
    turn = std::max(turn, std::abs(2 * kPi * m.k[i]));
  }
  return std::abs(f) <= 1e-6 * turn;
}

double coupling_residual(const CouplingMeasure& m, const double last[2], double phase) {
  if (!m.valid) return 0;
  double turns[2];
  unwrap_turns(m, last, phase, turns);
  double f = m.s - phase;
  for (int i = 0; i < m.angles; ++i) f += m.k[i] * turns[i];
  return f;
}

namespace {

Row gradient(const CouplingMeasure& m) {
  Row J = m.ds;
  for (int i = 0; i < m.angles; ++i) J += m.k[i] * m.dtheta[i];
  return J;
}

}  // namespace

PartRows coupling_rows(const CouplingMeasure& m, const double last[2], double phase) {
  PartRows out;
  if (!m.valid) return out;
  out.count = 1;
  out.J[0] = gradient(m);
  out.residual[0] = coupling_residual(m, last, phase);
  return out;
}

void coupling_corrections(const CouplingMeasure& m, const double last[2], double phase,
                          const Mobility& b1, const Mobility& b2, Vec3* dR1, Vec3* dR2, Vec3* dx1,
                          Vec3* dx2) {
  const double f = coupling_residual(m, last, phase);
  if (f == 0) return;
  const Row J = gradient(m);
  const Vec3 r1 = J.segment<3>(0).transpose(), t1 = J.segment<3>(3).transpose();
  const Vec3 r2 = J.segment<3>(6).transpose(), t2 = J.segment<3>(9).transpose();
  const Vec3 Ar1 = b1.A * r1, Ar2 = b2.A * r2;
  const double metric =
      r1.dot(Ar1) + b1.mu * t1.squaredNorm() + r2.dot(Ar2) + b2.mu * t2.squaredNorm();
  if (!(metric > 0)) return;
  const double lambda = f / metric;
  if (dR1) *dR1 -= lambda * Ar1;
  if (dR2) *dR2 -= lambda * Ar2;
  if (dx1) *dx1 -= lambda * b1.mu * t1;
  if (dx2) *dx2 -= lambda * b2.mu * t2;
}

}  // namespace dispcon
