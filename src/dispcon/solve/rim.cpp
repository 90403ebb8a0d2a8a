// A turn's reduced quasi-Newton step (rim.hpp). Along a cone's rim the Lagrangian's Hessian on
// the free directions is the Gauss-Newton term plus the bound's curvature times its multiplier,
// -nu g'' (for a cone nu [[0, 1/2], [1/2, cot theta]] in the twist and the turn across the rim):
// indefinite, coupling the directions, and no multiple of the metric. The pull's damped step
// stands for it by one number, set by a secant along each step, so it fits one direction at a
// time and converges linearly. Here the model lives on the null space of the rows the step holds
// (a few directions: two on a wrist's rim) and its curvature is measured, not guessed: BFGS on
// the reduced gradient's changes between kept poses (the reduced-Hessian quasi-Newton method of
// SQP, whose steps converge superlinearly).
#include "dispcon/solve/rim.hpp"

#include <algorithm>
#include <cmath>

namespace dispcon {

// Q times the identity's last n - rank columns, as Eigen's HouseholderSequence product computes
// it for a matrix of fewer than 48 reflectors (one reflector at a time, the last first; with 48 or
// more it applies them by blocks, in a workspace of its own on the heap), into Zn_.
template <typename QR>
void RimModel::null_space(const QR& qr, Eigen::Index n, Eigen::Index rank) {
  const auto q = qr.householderQ();
  Zn_.setZero(n, n - rank);
  Zn_.bottomRows(n - rank).setIdentity();
  reflect_.resize(n - rank);
  for (Eigen::Index k = q.length() - 1; k >= 0; --k) {
    Zn_.bottomRightCorner(n - k, n - rank)
        .applyHouseholderOnTheLeft(q.essentialVector(k), qr.hCoeffs().coeff(k), reflect_.data());
  }
}

bool RimModel::observe(const SolverState& s, const Group& group, int joint,
                       const std::vector<double>& band, double soft_band, const LetGo& let_go) {
  const size_t nv = group.bodies.size();
  if (nv == 0 || nv > kMostBodies) {
    reset();
    return false;
  }
  const auto n = static_cast<Eigen::Index>(6 * nv);
  // The hard rows (as a pull step gathers them) and the soft ones, with their Jacobians.
  // (Kept from call to call, so a pull's steps allocate them once.)
  Eigen::MatrixXd& hard = hard_;
  Eigen::MatrixXd& soft_j = soft_j_;
  Eigen::VectorXd& g = g_;
  soft_j.setZero(3 * kPartSlots, n);
  g.setZero(n);
  hard.setZero(3 * kPartSlots * static_cast<Eigen::Index>(group.joints.size()), n);
  Eigen::Index rows = 0, soft_rows = 0;
  PartRows parts[kPartSlots];
  for (int c : group.joints) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    const BodyState& b1 = s.bodies[static_cast<size_t>(js.b1)];
    const BodyState& b2 = s.bodies[static_cast<size_t>(js.b2)];
    const int v1 = b1.movable ? b1.n_var : -1;
    const int v2 = b2.movable ? b2.n_var : -1;
    if (c == joint) {
      s.rows(js, BoundTest{soft_band}, parts, true);
    } else {
      JointBounds t{BoundTest{band[static_cast<size_t>(c)]}};
      if (!let_go.parts.empty()) {
        t.let_go_parts = let_go.parts[static_cast<size_t>(c)];
        t.let_go = let_go.band;
      }
      s.rows(js, t, parts, true);
    }
    for (const PartRows& p : parts) {
      for (int k = 0; k < p.count; ++k) {
        Eigen::Index& at = c == joint ? soft_rows : rows;
        Eigen::MatrixXd& m = c == joint ? soft_j : hard;
        if (!p.J[k].allFinite() || !std::isfinite(p.residual[k])) {
          reset();
          return false;
        }
        if (v1 >= 0) m.block<1, 6>(at, 6 * v1) += p.J[k].segment<6>(0);
        if (v2 >= 0) m.block<1, 6>(at, 6 * v2) += p.J[k].segment<6>(6);
        if (c == joint) g += p.residual[k] * m.row(at).transpose();
        ++at;
      }
    }
  }
  // The free directions: the null space of the hard rows.
  if (rows == 0) {
    Zn_.setIdentity(n, n);
  } else if (rows <= kMostHardRows) {
    // A rank-revealing QR of the rows' transpose: its Q's last columns span what they leave.
    qr_.compute(hard.topRows(rows).transpose());
    qr_.setThreshold(1e-9);
    null_space(qr_, n, qr_.rank());
  } else {
    qr_wide_.compute(hard.topRows(rows).transpose());
    qr_wide_.setThreshold(1e-9);
    null_space(qr_wide_, n, qr_wide_.rank());
  }
  const Eigen::Index d = Zn_.cols();
  if (d > kMostFree) {
    reset();
    return false;
  }
  // Carried from the last pose: the basis of the new null space nearest the old one, so that the
  // reduced coordinates mean the same motions; where the held rows changed (a bound met or let
  // go) the model starts again.
  bool pair = observed_ && Z_.rows() == n && Z_.cols() == d && d > 0;
  if (pair) {
    svd_.compute(Zn_.transpose() * Z_, Eigen::ComputeFullU | Eigen::ComputeFullV);
    if (svd_.singularValues().minCoeff() > 0.9) {
      Zn_ = Zn_ * (svd_.matrixU() * svd_.matrixV().transpose());
    } else {
      pair = false;
    }
  }
  gzn_.noalias() = Zn_.transpose() * g;
  js_.noalias() = soft_j.topRows(soft_rows) * Zn_;
  gauss_newton_.noalias() = js_.transpose() * js_;
  if (pair) {
    // The displacement from the last pose, as Polisher::step moves a body (turned about its
    // centre, then its centre moved), in the reduced coordinates.
    step_.resize(n);
    for (size_t v = 0; v < nv; ++v) {
      const BodyState& b = s.bodies[static_cast<size_t>(group.bodies[v])];
      const Eigen::AngleAxisd turn(Mat3(b.R * R_[v].transpose()));
      step_.segment<3>(static_cast<Eigen::Index>(6 * v)) = turn.angle() * turn.axis();
      step_.segment<3>(static_cast<Eigen::Index>(6 * v + 3)) = b.G - G_[v];
    }
    sz_.noalias() = Zn_.transpose() * step_;
    y_ = gzn_ - gz_;
    const double sy = sz_.dot(y_);
    if (sz_.norm() > 0 && sy > 1e-12 * sz_.norm() * y_.norm() && y_.allFinite()) {
      if (B_.rows() != d) {
        // The first pair: the Gauss-Newton term, plus along the step what it leaves out, spread
        // evenly (the bounds' curvature, not yet told apart by direction).
        const double missing = (sy - sz_.dot(gauss_newton_ * sz_)) / sz_.squaredNorm();
        const double floor = 1e-6 * std::max(gauss_newton_.trace() / static_cast<double>(d), 1e-12);
        B_ = gauss_newton_;
        B_.diagonal().array() += std::max(missing, floor);
      }
      bs_.noalias() = B_ * sz_;
      const double sbs = sz_.dot(bs_);
      if (sbs > 0) B_ += y_ * y_.transpose() / sy - bs_ * bs_.transpose() / sbs;
    }
  } else {
    B_.resize(0, 0);
    radius_ = 0;
    validated_ = false;
  }
  Z_ = Zn_;
  gz_ = gzn_;
  R_.resize(nv);
  G_.resize(nv);
  for (size_t v = 0; v < nv; ++v) {
    const BodyState& b = s.bodies[static_cast<size_t>(group.bodies[v])];
    R_[v] = b.R;
    G_[v] = b.G;
  }
  observed_ = true;
  return true;
}

bool RimModel::propose(double max_rotation, std::vector<Vec6>& dq, double& predicted) const {
  const Eigen::Index d = Z_.cols();
  if (!observed_ || d == 0 || B_.rows() != d || !B_.allFinite()) return false;
  llt_.compute(B_);
  if (llt_.info() != Eigen::Success) return false;
  Vector& p = p_;
  p = -llt_.solve(gz_);
  const double radius = radius_ > 0 ? radius_ : HUGE_VAL;
  if (!p.allFinite()) return false;
  if (p.norm() > radius) p *= radius / p.norm();
  Vector& full = full_;
  full.noalias() = Z_ * p;
  const size_t nv = static_cast<size_t>(full.size() / 6);
  double turn = 0;
  for (size_t v = 0; v < nv; ++v) {
    turn = std::max(turn, full.segment<3>(static_cast<Eigen::Index>(6 * v)).norm());
  }
  const double scale = turn > max_rotation ? max_rotation / turn : 1;
  cut_short_ = scale < 1;
  p *= scale;
  dq.resize(nv);
  for (size_t v = 0; v < nv; ++v) {
    dq[v] = scale * full.segment<6>(static_cast<Eigen::Index>(6 * v));
  }
  predicted = -(gz_.dot(p) + 0.5 * p.dot(B_ * p));
  length_ = p.norm();
  return predicted > 0;
}

double RimModel::whole_gain() const {
  const Eigen::Index d = Z_.cols();
  if (!observed_ || d == 0 || B_.rows() != d) return HUGE_VAL;
  llt_.compute(B_);
  if (llt_.info() != Eigen::Success) return HUGE_VAL;
  const double g = 0.5 * gz_.dot(llt_.solve(gz_));
  return g >= 0 ? g : HUGE_VAL;
}

void RimModel::judge(double ratio, bool kept) {
  if (kept && ratio > 0.5 && ratio < 2) validated_ = true;
  if (kept && ratio > 0.5) {
    if (radius_ > 0) radius_ = std::max(radius_, 2 * length_);
  } else if (!kept || ratio < 0.1) {
    radius_ = 0.25 * length_;
  }
}

void RimModel::reset() {
  observed_ = validated_ = false;
  B_.resize(0, 0);
  radius_ = length_ = 0;
}

}  // namespace dispcon
