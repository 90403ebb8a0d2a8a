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
// place, pre-ordered in the upper triangle (big_->slots_ remembers where each entry lands), so the
// factorisation reads the matrix without a copy.
bool Polisher::factor_sparse(const SolverState& s, double lambda) {
  const int m = static_cast<int>(w_->rows_.size());
  factored_ = false;
  if (!big_) big_ = std::make_unique<Large>();
  const bool same = same_pattern();
  // row_products() need not list the rows again
  lists_current_ = same && w_->caches_.of(Caches::kLists, this);
  if (!same) {
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
      analyze_rows();
    }
    big_->analyzed_pattern_.resize(2 * static_cast<size_t>(m));
    for (int a = 0; a < m; ++a) {
      big_->analyzed_pattern_[2 * static_cast<size_t>(a)] = w_->rows_[static_cast<size_t>(a)].v1;
      big_->analyzed_pattern_[2 * static_cast<size_t>(a) + 1] =
          w_->rows_[static_cast<size_t>(a)].v2;
    }
    analyzed_ = true;
  }
  // The damping is relative to the largest diagonal entry of J M^-1 J^T; a pull's own damping
  // (soft_) is then put in the diagonal's units.
  double scale = 0;
  if (kkt_) {
    for (const Entry& e : w_->rows_) {
      const double d1 = e.v1 >= 0 ? e.j1.dot(apply_inverse_mass(body(e.v1), e.j1)) : 0;
      const double d2 = e.v2 >= 0 ? e.j2.dot(apply_inverse_mass(body(e.v2), e.j2)) : 0;
      scale = std::max(scale, d1 + d2);
    }
    if (!(scale > 0)) return false;
    for (double& d : w_->soft_) d *= scale;
    big_->firsts_ = 0;  // the first steps' residuals were of the last factorisation
    if (!factor_blocks(s, lambda * scale)) return false;
    factored_ = true;
    return solve_blocks(w_->residual_);
  }
  // The rows form: the row products first, whose diagonal entries are then the two bodies' terms
  // of each row, d1 + d2, the very sums a pass of their own computed before (one pass over the
  // rows fewer each step); then the damping on the diagonal.
  double* values = big_->ldlt_.values.data();
  std::fill(big_->ldlt_.values.begin(), big_->ldlt_.values.end(), 0.0);
  const int* slot = big_->slots_.data();
  row_products([&](int, int, double v) { values[*slot++] += v; });
  const int* diagonal = slot;  // the last m slots: each row's diagonal entry
  for (int a = 0; a < m; ++a) scale = std::max(scale, values[diagonal[a]]);
  if (!(scale > 0)) return false;
  const double mu = lambda * scale;
  for (double& d : w_->soft_) d *= scale;
  for (int a = 0; a < m; ++a) values[diagonal[a]] += mu + soft(a);
  if (!big_->ldlt_.factorize()) return false;
  return solve_factored();
}

// Whether the rows join the same bodies as when the sparse system was analysed.
bool Polisher::same_pattern() const {
  const auto& rows = w_->rows_;
  if (!analyzed_ || big_->analyzed_pattern_.size() != 2 * rows.size()) return false;
  for (size_t a = 0; a < rows.size(); ++a) {
    if (rows[a].v1 != big_->analyzed_pattern_[2 * a] ||
        rows[a].v2 != big_->analyzed_pattern_[2 * a + 1]) {
      return false;
    }
  }
  return true;
}

// The rows form's step from the current residuals with its factorisation.
bool Polisher::solve_factored() {
  const int m = static_cast<int>(w_->rows_.size());
  double* x = big_->ldlt_.rhs();
  for (int a = 0; a < m; ++a) {
    x[big_->order_[static_cast<size_t>(a)]] = -w_->residual_[static_cast<size_t>(a)];
  }
  big_->ldlt_.solve();
  w_->y_.resize(static_cast<size_t>(m));
  bool finite = true;
  for (int a = 0; a < m; ++a) {
    const double y = x[big_->order_[static_cast<size_t>(a)]];
    w_->y_[static_cast<size_t>(a)] = y;
    finite = finite && std::isfinite(y);
  }
  return finite;
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

// Orders, places and analyses the rows form J M^-1 J^T, whose entry (a, b) is there when rows a
// and b share a body, straight from each body's rows (no pass computes the products). In large
// systems the fill-reducing order is found on blocks, each joint's rows, which share their
// neighbours: AMD on the 300,000 rows of a 100,000-link chain took 0.2 s, on its 100,000 joints
// 5 ms. Below kBlockOrdering unknowns the analysis is cheap and AMD on single unknowns leaves
// less fill, which every drag frame pays. The pattern was once gathered from the row products
// themselves, three passes computing every product and sorting every column of the result:
// most of the 100,000-link chain's analysis.
void Polisher::analyze_rows() {
  const int n = static_cast<int>(w_->rows_.size());
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
  // The blocks' pattern (lower triangle): each block's diagonal, and every two blocks with rows
  // on the same body (a body's rows are listed in row order, so a block's are next to each other).
  list_rows_by_body();
  const std::vector<int>& var_start = w_->var_start_;
  const HugeVector<std::pair<int, int>>& var_rows = w_->var_rows_;
  std::vector<std::pair<int, int>>& pairs = w_->block_pairs_;
  pairs.clear();
  for (int b = 0; b < blocks; ++b) pairs.emplace_back(b, b);
  std::vector<int>& here = w_->blocks_here_;
  for (int v = 0; v < nv_; ++v) {
    here.clear();
    for (int p = var_start[static_cast<size_t>(v)]; p < var_start[static_cast<size_t>(v) + 1];
         ++p) {
      const int b = block[static_cast<size_t>(var_rows[static_cast<size_t>(p)].first)];
      if (here.empty() || here.back() != b) here.push_back(b);
    }
    for (size_t i = 0; i < here.size(); ++i) {
      for (size_t j = 0; j < i; ++j)
        pairs.emplace_back(std::max(here[i], here[j]), std::min(here[i], here[j]));
    }
  }
  Eigen::SparseMatrix<double> lower;
  compress(
      blocks,
      [&](auto&& f) {
        for (const auto& [r, c] : pairs) f(r, c);
      },
      lower, here, w_->place_, w_->column_);
  std::fill(lower.valuePtr(), lower.valuePtr() + lower.nonZeros(), 1.0);
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  Eigen::AMDOrdering<int>()(lower.selfadjointView<Eigen::Lower>(), inverse);
  // Eigen's orderings return the inverse permutation: inverse.indices()(k) is the k-th block
  // to eliminate. Row a goes to big_->order_[a]: the blocks in that order, each block's rows in
  // theirs.
  big_->order_.resize(static_cast<size_t>(n));
  std::vector<int>& row_at = w_->place_;  // row_at[big_->order_[a]] = a
  row_at.resize(static_cast<size_t>(n));
  int at = 0;
  for (int k = 0; k < blocks; ++k) {
    const auto b = static_cast<size_t>(inverse.indices()(k));
    for (int i = start[b]; i < start[b + 1]; ++i) {
      row_at[static_cast<size_t>(at)] = i;
      big_->order_[static_cast<size_t>(i)] = at++;
    }
  }
  // The system itself, reordered, in the upper triangle: column big_->order_[a] holds the rows that
  // share a body with row a and come no later, sorted.
  size_t most = static_cast<size_t>(n);
  for (const Entry& e : w_->rows_) {
    for (int v : {e.v1, e.v2}) {
      if (v >= 0) {
        most += static_cast<size_t>(var_start[static_cast<size_t>(v) + 1] -
                                    var_start[static_cast<size_t>(v)]);
      }
    }
  }
  HugeVector<int>& outer = big_->ldlt_.starts;
  HugeVector<int>& inner = big_->ldlt_.rows;
  outer.resize(static_cast<size_t>(n) + 1);
  inner.resize(most);
  std::vector<int>& column = w_->column_rows_;
  int kept = 0;
  for (int c = 0; c < n; ++c) {
    const Entry& e = w_->rows_[static_cast<size_t>(row_at[static_cast<size_t>(c)])];
    column.assign(1, c);
    for (int v : {e.v1, e.v2}) {
      if (v < 0) continue;
      for (int p = var_start[static_cast<size_t>(v)]; p < var_start[static_cast<size_t>(v) + 1];
           ++p) {
        const int r = big_->order_[static_cast<size_t>(var_rows[static_cast<size_t>(p)].first)];
        if (r < c) column.push_back(r);
      }
    }
    std::sort(column.begin(), column.end());
    outer[static_cast<size_t>(c)] = kept;
    for (size_t i = 0; i < column.size(); ++i) {
      if (i == 0 || column[i] != column[i - 1]) inner[static_cast<size_t>(kept++)] = column[i];
    }
  }
  outer[static_cast<size_t>(n)] = kept;
  inner.resize(static_cast<size_t>(kept));
  big_->ldlt_.values.resize(static_cast<size_t>(kept));
  // Where each value lands, in the order factor_sparse() writes them: the row products, then the
  // diagonal.
  auto slot = [&](int a, int b) {
    const int pa = big_->order_[static_cast<size_t>(a)], pb = big_->order_[static_cast<size_t>(b)];
    const int c = std::max(pa, pb), r = std::min(pa, pb);
    int* first = inner.data() + outer[static_cast<size_t>(c)];
    return static_cast<int>(
        std::lower_bound(first, inner.data() + outer[static_cast<size_t>(c) + 1], r) -
        inner.data());
  };
  size_t writes = static_cast<size_t>(n);
  for (int v = 0; v < nv_; ++v) {
    const auto k = static_cast<size_t>(var_start[static_cast<size_t>(v) + 1] -
                                       var_start[static_cast<size_t>(v)]);
    writes += k * (k + 1) / 2;
  }
  big_->slots_.clear();
  big_->slots_.reserve(writes);
  row_products<false>([&](int a, int b, double) { big_->slots_.push_back(slot(a, b)); });
  for (int a = 0; a < n; ++a) big_->slots_.push_back(slot(a, a));
  big_->ldlt_.analyze();
}

}  // namespace dispcon
