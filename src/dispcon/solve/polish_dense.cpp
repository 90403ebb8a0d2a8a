// The Newton polish's factorisation for small groups (up to kDenseRows rows): J M^-1 J^T
// assembled dense, then a Cholesky written for these sizes, or a pivoting LDLT when rounding
// defeats it.
#include <algorithm>
#include <cmath>

#include "dispcon/solve/polish.hpp"

namespace dispcon {

namespace {

// Solves A y = b in place for a small symmetric positive definite A given by its lower triangle
// (column-major, overwritten by the factor L). Column-oriented so every inner loop runs over
// contiguous memory; for the few dozen rows of a mechanism's group this beats the general
// blocked factorisations. Returns false when a pivot is not positive.
bool cholesky_solve(Eigen::Ref<Eigen::MatrixXd> A, Eigen::Ref<Eigen::VectorXd> y) {
  const Eigen::Index m = A.rows();
  double* a = A.data();
  for (Eigen::Index j = 0; j < m; ++j) {
    double* cj = a + j * m;
    for (Eigen::Index k = 0; k < j; ++k) {
      const double* ck = a + k * m;
      const double f = ck[j];
      if (f == 0) continue;
      for (Eigen::Index i = j; i < m; ++i) cj[i] -= f * ck[i];
    }
    if (!(cj[j] > 0)) return false;
    const double d = std::sqrt(cj[j]);
    cj[j] = d;
    const double inv = 1 / d;
    for (Eigen::Index i = j + 1; i < m; ++i) cj[i] *= inv;
  }
  double* x = y.data();
  for (Eigen::Index j = 0; j < m; ++j) {  // L z = b
    const double* cj = a + j * m;
    x[j] /= cj[j];
    const double xj = x[j];
    for (Eigen::Index i = j + 1; i < m; ++i) x[i] -= xj * cj[i];
  }
  for (Eigen::Index j = m - 1; j >= 0; --j) {  // L^T y = z
    const double* cj = a + j * m;
    double sum = x[j];
    for (Eigen::Index i = j + 1; i < m; ++i) sum -= cj[i] * x[i];
    x[j] = sum / cj[j];
  }
  return true;
}

}  // namespace

bool Polisher::factor(const SolverState& s, double lambda) {
  return static_cast<int>(w_->rows_.size()) <= kDenseRows ? factor_dense(lambda)
                                                          : factor_sparse(s, lambda);
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
    for (int a = 0; a < m; ++a) A(a, a) += soft(a) * scale;
    return scale;
  };
  if (!(assemble() > 0)) return false;
  y = -r;
  if (cholesky_solve(A, y)) return y.allFinite();
  assemble();
  w_->full_ = A.selfadjointView<Eigen::Lower>();
  w_->dense_ldlt_.compute(w_->full_);
  if (w_->dense_ldlt_.info() != Eigen::Success) return false;
  y = w_->dense_ldlt_.solve(-r);
  return y.allFinite();
}

}  // namespace dispcon
