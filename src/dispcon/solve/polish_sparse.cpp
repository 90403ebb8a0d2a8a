// The Newton polish's factorisation for large groups: sparse, in the form with fewer entries,
// keeping the fill-reducing order and the symbolic analysis while the rows keep their pattern.
#include <Eigen/OrderingMethods>
#include <algorithm>

#include "dispcon/solve/polish.hpp"

namespace dispcon {

// Large groups are solved sparse, in one of two forms with the same solution: J M^-1 J^T
// itself (chains: a few rows per body), or the saddle-point system of polish_blocks.cpp when
// bodies carry many rows (loops sharing bodies), whose every row only touches its two bodies.
// The form with fewer entries is taken; that was also the faster one on the benchmarks' chains
// and grids. J M^-1 J^T is factored by Eigen's simplicial LDLT: while the pattern holds, the
// fill-reducing order (AMD) and the symbolic analysis are kept, and the values are written in
// place, pre-ordered in the upper triangle (slots_ remembers where each entry lands), so the
// factorisation reads the matrix without a copy.
bool Polisher::factor_sparse(const SolverState& s, double lambda) {
  const int m = static_cast<int>(w_->rows_.size());
  double scale = 0;  // the largest diagonal entry of J M^-1 J^T
  for (const Entry& e : w_->rows_) {
    scale = std::max(scale, (e.v1 >= 0 ? e.j1.dot(e.u1) : 0) + (e.v2 >= 0 ? e.j2.dot(e.u2) : 0));
  }
  if (!(scale > 0)) return false;
  const double mu = lambda * scale;
  auto rows_form = [&](auto&& f) {
    couplings(f);
    for (int a = 0; a < m; ++a) f(a, a, mu);
  };
  factored_ = false;
  if (!same_pattern()) {
    std::vector<double>& per_body = w_->rows_per_body_;
    per_body.assign(static_cast<size_t>(nv_), 0.0);
    for (const Entry& e : w_->rows_) {
      if (e.v1 >= 0) per_body[static_cast<size_t>(e.v1)] += 1;
      if (e.v2 >= 0) per_body[static_cast<size_t>(e.v2)] += 1;
    }
    double rows_entries = 0;  // lower triangle, counting rows that share two bodies twice
    for (double k : per_body) rows_entries += k * (k + 1) / 2;
    const double kkt_entries = 9.0 * nv_ + 13.0 * m;
    kkt_ = kkt_entries < rows_entries;
    if (kkt_) {
      analyze_blocks();
    } else {
      analyze(m, rows_form);
    }
    analyzed_pattern_ = w_->pattern_;
    analyzed_ = true;
  }
  if (kkt_) {
    if (!factor_blocks(s, mu)) return false;
    factored_ = true;
    return solve_blocks();
  }
  double* values = sparse_.valuePtr();
  std::fill(values, values + sparse_.nonZeros(), 0.0);
  size_t visit = 0;
  rows_form([&](int, int, double v) { values[slots_[visit++]] += v; });
  sparse_ldlt_.factorize(sparse_);
  if (sparse_ldlt_.info() != Eigen::Success) return false;
  return solve_factored();
}

// Whether the rows join the same bodies as when the sparse system was analysed.
bool Polisher::same_pattern() {
  w_->pattern_.clear();
  for (const Entry& e : w_->rows_) w_->pattern_.push_back(e.v1), w_->pattern_.push_back(e.v2);
  return analyzed_ && w_->pattern_ == analyzed_pattern_;
}

// The rows form's step from the current residuals with its factorisation.
bool Polisher::solve_factored() {
  const int m = static_cast<int>(w_->rows_.size());
  rhs_.setZero(m);
  for (int a = 0; a < m; ++a) rhs_(order_(a)) = -w_->residual_[static_cast<size_t>(a)];
  solution_ = sparse_ldlt_.solve(rhs_);
  w_->y_.resize(static_cast<size_t>(m));
  for (int a = 0; a < m; ++a) w_->y_[static_cast<size_t>(a)] = solution_(order_(a));
  return solution_.allFinite();
}

// Orders, places and analyses an n x n system given by its lower-triangle entries (in a fixed
// order). In large systems the fill-reducing order is found on blocks, each joint's rows, which
// share their neighbours: AMD on the 300,000 rows of a 100,000-link chain took 0.2 s, on its
// 100,000 joints 5 ms. Below kBlockOrdering unknowns the analysis is cheap and AMD on single
// unknowns leaves less fill, which every drag frame pays.
template <typename Form>
void Polisher::analyze(int n, Form&& form) {
  std::vector<int>& start = w_->block_start_;
  start.clear();
  if (n < kBlockOrdering) {
    for (int i = 0; i < n; ++i) start.push_back(i);
  } else {
    for (size_t k = 0; k + 1 < w_->joint_rows_.size(); ++k) start.push_back(w_->joint_rows_[k]);
  }
  start.push_back(n);
  const int blocks = static_cast<int>(start.size()) - 1;
  std::vector<int>& block = w_->block_of_;
  block.resize(static_cast<size_t>(n));
  for (int b = 0; b < blocks; ++b) {
    std::fill(block.begin() + start[static_cast<size_t>(b)],
              block.begin() + start[static_cast<size_t>(b) + 1], b);
  }
  // The blocks' pattern; the entries come block pair by block pair, so repeats are mostly next
  // to each other (setFromTriplets merges the rest).
  w_->triplets_.clear();
  int last_a = -1, last_b = -1;
  size_t count = 0;
  form([&](int a, int b, double) {
    ++count;
    const int ba = block[static_cast<size_t>(a)], bb = block[static_cast<size_t>(b)];
    if (ba == last_a && bb == last_b) return;
    last_a = ba;
    last_b = bb;
    w_->triplets_.emplace_back(std::max(ba, bb), std::min(ba, bb), 1.0);
  });
  Eigen::SparseMatrix<double> lower(blocks, blocks);
  lower.setFromTriplets(w_->triplets_.begin(), w_->triplets_.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  Eigen::AMDOrdering<int>()(lower.selfadjointView<Eigen::Lower>(), inverse);
  // Eigen's orderings return the inverse permutation: inverse.indices()(k) is the k-th block
  // to eliminate. Row a goes to order_[a]: the blocks in that order, each block's rows in theirs.
  order_.resize(n);
  int at = 0;
  for (int k = 0; k < blocks; ++k) {
    const auto b = static_cast<size_t>(inverse.indices()(k));
    for (int i = start[b]; i < start[b + 1]; ++i) order_(i) = at++;
  }
  w_->triplets_.clear();
  w_->triplets_.reserve(count);
  form([&](int a, int b, double v) { w_->triplets_.push_back(reordered(a, b, v)); });
  sparse_.resize(n, n);
  sparse_.setFromTriplets(w_->triplets_.begin(), w_->triplets_.end());
  sparse_.makeCompressed();
  slots_.clear();
  slots_.reserve(count);
  form([&](int a, int b, double) { slots_.push_back(slot(reordered(a, b))); });
  sparse_ldlt_.analyzePattern(sparse_);
}

// Entry (a, b) in the reordered matrix's upper triangle.
Eigen::Triplet<double> Polisher::reordered(int a, int b, double v) const {
  const int pa = order_(a), pb = order_(b);
  return Eigen::Triplet<double>(std::min(pa, pb), std::max(pa, pb), v);
}

// Index in sparse_'s values of an upper-triangle entry (column-major).
int Polisher::slot(const Eigen::Triplet<double>& t) const {
  const int* inner = sparse_.innerIndexPtr();
  const int* begin = inner + sparse_.outerIndexPtr()[t.col()];
  const int* end = inner + sparse_.outerIndexPtr()[t.col() + 1];
  return static_cast<int>(std::lower_bound(begin, end, t.row()) - inner);
}

}  // namespace dispcon
