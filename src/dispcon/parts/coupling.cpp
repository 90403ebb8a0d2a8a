#include "dispcon/parts/coupling.hpp"

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

double coupling_residual(const CouplingMeasure& m, const double last[2], double phase) {
  if (!m.valid) return 0;
  double f = m.s - phase;
  for (int i = 0; i < m.angles; ++i) f += m.k[i] * unwrap(m.theta[i], last[i]);
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
