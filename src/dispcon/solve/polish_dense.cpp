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
    couplings([&](int a, int b, double v) { A(a, b) += v; });
    const double scale = A.diagonal().maxCoeff();
    A.diagonal().array() += lambda * scale;
    // A pull's own damping (none elsewhere: adding 0 a row cost 110 instructions a step).
    if (!w_->soft_.empty()) {
      for (int a = 0; a < m; ++a) A(a, a) += soft(a) * scale;
    }
    return scale;
  };
  if (!(assemble() > 0)) return false;
  y = -r;
  static_assert(kDenseRows <= kPatternRows, "PatternCholesky takes the dense systems");
  if (w_->chol_.factor(A.data(), m)) {
    w_->chol_.solve(A.data(), y.data());
    return y.allFinite();
  }
  assemble();
  w_->full_ = A.selfadjointView<Eigen::Lower>();
  w_->dense_ldlt_.compute(w_->full_);
  if (w_->dense_ldlt_.info() != Eigen::Success) return false;
  y = w_->dense_ldlt_.solve(-r);
  return y.allFinite();
}

}  // namespace dispcon
