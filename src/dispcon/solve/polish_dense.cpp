// The Newton polish's factorisation for small groups (up to kDenseRows rows): J M^-1 J^T
// assembled dense, then a Cholesky on its non-zero pattern (pattern_cholesky.hpp), or a
// pivoting LDLT when rounding defeats it.
#include <algorithm>

#include "dispcon/solve/polish.hpp"

namespace dispcon {

bool Polisher::factor(const SolverState& s, double lambda) {
  return dense() ? factor_dense(lambda) : factor_sparse(s, lambda);
}

bool Polisher::factor_dense(double lambda) {
  const int m = static_cast<int>(w_->rows_.size());
  const Eigen::Map<const Eigen::VectorXd> r(w_->residual_.data(), m);
  // Lower triangle only; Cholesky first (the regularised matrix is positive definite), the
  // pivoting LDLT only when rounding defeats it.
  w_->dense_.resize(static_cast<size_t>(m) * static_cast<size_t>(m));
  w_->y_.resize(static_cast<size_t>(m));
  Eigen::Map<Eigen::MatrixXd> A(w_->dense_.data(), m, m);
  Eigen::Map<Eigen::VectorXd> y(w_->y_.data(), m);
  auto assemble = [&] {
    // The whole matrix in one fill, not the lower triangle column by column (a call each): the
    // upper triangle is never read.
    std::fill(w_->dense_.begin(), w_->dense_.end(), 0.0);
    row_products([&](int a, int b, double v) { A(a, b) += v; });
    const double scale = A.diagonal().maxCoeff();
    A.diagonal().array() += lambda * scale;
    // A pull's own damping (none elsewhere: adding 0 a row cost 110 instructions a step).
    if (!w_->soft_.empty()) {
      for (int a = 0; a < m; ++a) A(a, a) += soft(a) * scale;
    }
    return scale;
  };
  const double scale = assemble();
  if (!(scale > 0)) return false;
  y = -r;
  static_assert(kDenseRows <= kPatternRows, "PatternCholesky takes the dense systems");
  if (w_->chol_.factor(A.data(), m)) {
    w_->chol_.solve(A.data(), y.data());
    small_factored_ = small_chord_ && w_->soft_.empty();
    if (small_factored_) {
      w_->caches_.made(Caches::kChord, this);
      small_damping_ = lambda * scale;
      small_scale_ = scale;
      small_free_ = -1;
    }
    return y.allFinite();
  }
  assemble();
  w_->full_ = A.selfadjointView<Eigen::Lower>();
  w_->dense_ldlt_.compute(w_->full_);
  if (w_->dense_ldlt_.info() != Eigen::Success) return false;
  y = w_->dense_ldlt_.solve(-r);
  return y.allFinite();
}

// Whether the rows just factored leave the group no free motion: as many of them independent as
// the group has unknowns (six a body). Then the poses that meet the joints are isolated, and a
// chord step (this factorisation reused at the next poses) closes in on the same answer as Newton
// steps would, to within what it leaves of the residual; with free motion it would not (its step
// lies in the old Jacobian's row space, and the poses would slide along the free motion).
// The Cholesky's pivot L_jj^2 is what row j adds to the rows before it: its squared distance from
// their span (in the metric of M^-1) plus the damping lambda * scale. A row in that span (a
// redundant row: the out-of-plane rows of a planar linkage posed in 3D) has a pivot of the
// damping times one plus its coefficients' squares; an independent row at least its squared
// distance. Each pivot must fall clearly in one class or the other: dependent up to kDependent
// times the damping, independent from kIndependent of the largest diagonal (at the least
// damping, 1e-12, ten thousand times above); a pivot in between (a pose near a singular one,
// where rows are nearly dependent and the classes blur) or a damping too large to tell them
// apart takes no chord step. Rounding in the factor is about 1e-15 of the diagonal, far below
// both. (The 400 four-bars: 12 pivots from 1.8e-2 of the scale, 3 up to 15 times the damping.)
bool Polisher::no_free_motion() const {
  constexpr double kDependent = 100;
  constexpr double kIndependent = 1e-6;
  const double damping = small_damping_;
  const double dependent = kDependent * damping;
  const double independent = kIndependent * small_scale_;
  if (!(dependent <= 1e-3 * independent)) return false;  // the classes too close
  const int m = static_cast<int>(w_->rows_.size());
  int rows = 0;
  for (int j = 0; j < m; ++j) {
    const double l = w_->dense_[static_cast<size_t>(j) * static_cast<size_t>(m) + j];
    const double pivot = l * l - damping;
    if (pivot >= independent) {
      ++rows;
    } else if (!(pivot <= dependent)) {
      return false;
    }
  }
  return rows == 6 * nv_;
}

}  // namespace dispcon
