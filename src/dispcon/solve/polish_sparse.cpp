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
    const double d1 = e.v1 >= 0 ? e.j1.dot(apply_inverse_mass(body(e.v1), e.j1)) : 0;
    const double d2 = e.v2 >= 0 ? e.j2.dot(apply_inverse_mass(body(e.v2), e.j2)) : 0;
    scale = std::max(scale, d1 + d2);
  }
  if (!(scale > 0)) return false;
  const double mu = lambda * scale;
  for (double& d : w_->soft_) d *= scale;  // a pull's own damping, now in the diagonal's units
  auto rows_form = [&](auto&& f) {
    couplings(f);
    for (int a = 0; a < m; ++a) f(a, a, mu + soft(a));
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
    analyzed_pattern_.clear();
    for (const Entry& e : w_->rows_) {
      analyzed_pattern_.push_back(e.v1), analyzed_pattern_.push_back(e.v2);
    }
    analyzed_ = true;
  }
  if (kkt_) {
    if (!factor_blocks(s, mu)) return false;
    factored_ = true;
    return solve_blocks(w_->residual_);
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
bool Polisher::same_pattern() const {
  const auto& rows = w_->rows_;
  if (!analyzed_ || analyzed_pattern_.size() != 2 * rows.size()) return false;
  for (size_t a = 0; a < rows.size(); ++a) {
    if (rows[a].v1 != analyzed_pattern_[2 * a] || rows[a].v2 != analyzed_pattern_[2 * a + 1]) {
      return false;
    }
  }
  return true;
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

// Lays out an n x n pattern in `matrix`, compressed, each column's rows sorted and repeats
// merged, from the entries that `entries(f)` gives as f(row, column), the same ones in the same
// order each time it is called: once to count them per column, once to place them. where[k] is
// the index in matrix's values of the k-th entry. Built in place: a list of triplets and Eigen's
// setFromTriplets (which sorts through a transposed copy) cost the 100,000-link chain's first
// step about 0.35 s, most of it the first touch of their memory.
template <typename Entries>
void compress(int n, Entries&& entries, Eigen::SparseMatrix<double>& matrix,
              std::vector<int>& where, std::vector<int>& scratch,
              std::vector<std::pair<int, int>>& column) {
  matrix.resize(n, n);
  int* outer = matrix.outerIndexPtr();  // n + 1 zeros after resize
  size_t count = 0;
  entries([&](int, int c) { ++outer[c + 1], ++count; });
  for (int c = 0; c < n; ++c) outer[c + 1] += outer[c];
  matrix.resizeNonZeros(static_cast<Eigen::Index>(count));
  int* inner = matrix.innerIndexPtr();
  scratch.assign(outer, outer + n);  // the next free place of each column
  where.resize(count);
  size_t k = 0;
  entries([&](int r, int c) {
    const int at = scratch[static_cast<size_t>(c)]++;
    inner[at] = r;
    where[k++] = at;
  });
  // Each column sorted by row, its repeats merged, moved down over the places freed before it;
  // scratch maps a place as counted to the place it ends in.
  scratch.resize(count);
  int kept = 0;
  for (int c = 0; c < n; ++c) {
    column.clear();
    for (int at = outer[c]; at < outer[c + 1]; ++at) column.emplace_back(inner[at], at);
    std::sort(column.begin(), column.end());
    outer[c] = kept;
    for (size_t i = 0; i < column.size(); ++i) {
      if (i == 0 || column[i].first != column[i - 1].first) inner[kept++] = column[i].first;
      scratch[static_cast<size_t>(column[i].second)] = kept - 1;
    }
  }
  outer[n] = kept;
  matrix.resizeNonZeros(kept);
  std::fill(matrix.valuePtr(), matrix.valuePtr() + kept, 0.0);
  for (int& at : where) at = scratch[static_cast<size_t>(at)];
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
  // The blocks' pattern (lower triangle); the entries come block pair by block pair, so repeats
  // are mostly next to each other and are dropped there (compress merges the rest).
  std::vector<std::pair<int, int>>& pairs = w_->block_pairs_;
  pairs.clear();
  form([&](int a, int b, double) {
    const int ba = block[static_cast<size_t>(a)], bb = block[static_cast<size_t>(b)];
    const std::pair<int, int> p(std::max(ba, bb), std::min(ba, bb));
    if (pairs.empty() || pairs.back() != p) pairs.push_back(p);
  });
  Eigen::SparseMatrix<double> lower;
  compress(
      blocks,
      [&](auto&& f) {
        for (const auto& [r, c] : pairs) f(r, c);
      },
      lower, slots_, w_->place_, w_->column_);
  std::fill(lower.valuePtr(), lower.valuePtr() + lower.nonZeros(), 1.0);
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
  // The system itself, reordered, in the upper triangle; slots_ remembers where each entry lands.
  compress(
      n,
      [&](auto&& f) {
        form([&](int a, int b, double) {
          const int pa = order_(a), pb = order_(b);
          f(std::min(pa, pb), std::max(pa, pb));
        });
      },
      sparse_, slots_, w_->place_, w_->column_);
  sparse_ldlt_.analyzePattern(sparse_);
}

}  // namespace dispcon
