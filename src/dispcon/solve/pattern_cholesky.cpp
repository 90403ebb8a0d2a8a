#include "dispcon/solve/pattern_cholesky.hpp"

#include <algorithm>
#include <cmath>

namespace dispcon {

namespace {

// Sets of rows 0 ... 64 W - 1, each W words at `w`, visited in increasing order. One word where
// it will do: the second word's loops cost more than the arithmetic in a system of 15 rows.
template <int W>
void add(std::uint64_t* w, int i) {
  w[i >> 6] |= std::uint64_t{1} << (i & 63);
}
template <int W>
int first(const std::uint64_t* w) {  // the smallest row (the set must not be empty)
  for (int h = 0;; ++h) {
    if (w[h]) return 64 * h + __builtin_ctzll(w[h]);
  }
}
template <int W>
bool empty(const std::uint64_t* w) {
  std::uint64_t any = 0;
  for (int h = 0; h < W; ++h) any |= w[h];
  return any == 0;
}
// Adds the rows of `r` past row p (a child column's rows, to its parent p).
template <int W>
void add_below(std::uint64_t* w, const std::uint64_t* r, int p) {
  for (int h = 0; h < W; ++h) {
    const int below = p - 64 * h;  // bits of word h up to row p are dropped
    const std::uint64_t keep = below < 0     ? ~std::uint64_t{0}
                               : below >= 63 ? 0
                                             : ~std::uint64_t{0} << (below + 1);
    w[h] |= r[h] & keep;
  }
}
// f(i) for each row i >= from, in increasing order.
template <int W, typename F>
void each_from(const std::uint64_t* w, int from, F&& f) {
  for (int h = from >> 6; h < W; ++h) {
    std::uint64_t bits = w[h];
    if (h == from >> 6) bits &= ~std::uint64_t{0} << (from & 63);
    for (; bits; bits &= bits - 1) f(64 * h + __builtin_ctzll(bits));
  }
}
template <int W, typename F>
void each(const std::uint64_t* w, F&& f) {
  each_from<W>(w, 0, f);
}

// The non-zero places of A below its diagonal (a value that is not a number counts), column by
// column, into `found` (W words a column). (A branchless test a place, and SSE2's two places a
// comparison, each took more instructions in the 400 four-bars than this branch.)
template <int W>
void find_places(const double* a, int m, std::uint64_t* found) {
  std::fill_n(found, static_cast<long>(m) * W, 0);
  for (int k = 0; k < m; ++k) {
    const double* ck = a + static_cast<long>(k) * m;
    std::uint64_t* fk = found + static_cast<long>(k) * W;
    for (int i = k + 1; i < m; ++i) {
      if (ck[i] != 0) add<W>(fk, i);
    }
  }
}

template <int W>
void solve_on(const double* a, int m, const std::uint64_t* col, double* y) {
  for (int j = 0; j < m; ++j) {  // L z = b
    const double* cj = a + static_cast<long>(j) * m;
    y[j] /= cj[j];
    const double yj = y[j];
    each<W>(col + static_cast<long>(j) * W, [&](int i) { y[i] -= yj * cj[i]; });
  }
  for (int j = m - 1; j >= 0; --j) {  // L^T y = z
    const double* cj = a + static_cast<long>(j) * m;
    double sum = y[j];
    each<W>(col + static_cast<long>(j) * W, [&](int i) { sum -= cj[i] * y[i]; });
    y[j] = sum / cj[j];
  }
}

// col: the places of L below its diagonal, from A's (`given`) and the fill, which column k
// passes to its parent in the elimination tree (the first row below its diagonal); row: the
// columns k < j where row j of L may be non-zero.
template <int W>
void analyze(int m, const std::uint64_t* given, std::uint64_t* col, std::uint64_t* row) {
  std::copy_n(given, static_cast<long>(m) * W, col);
  std::fill_n(row, static_cast<long>(m) * W, 0);
  for (int k = 0; k < m; ++k) {
    const std::uint64_t* ck = col + static_cast<long>(k) * W;
    if (empty<W>(ck)) continue;
    const int parent = first<W>(ck);
    add_below<W>(col + static_cast<long>(parent) * W, ck, parent);
    each<W>(ck, [&](int i) { add<W>(row + static_cast<long>(i) * W, k); });
  }
}

int words(int m) {
  return m <= 64 ? 1 : 2;
}

}  // namespace

bool PatternCholesky::factor(double* a, int m) {
  static_assert(kPatternRows == 128, "one or two words a column");
  const int w = words(m);
  const size_t size = static_cast<size_t>(m) * static_cast<size_t>(w);
  if (found_.size() < size) found_.resize(size), given_.resize(size);
  if (w == 1) {
    find_places<1>(a, m, found_.data());
  } else {
    find_places<2>(a, m, found_.data());
  }
  if (m != m_ ||
      !std::equal(found_.begin(), found_.begin() + static_cast<long>(size), given_.begin())) {
    std::swap(found_, given_);
    col_.resize(size);
    row_.resize(size);
    if (w == 1) {
      analyze<1>(m, given_.data(), col_.data(), row_.data());
      lists<1>(m);
    } else {
      analyze<2>(m, given_.data(), col_.data(), row_.data());
      lists<2>(m);
    }
    m_ = m;
  }
  // The dense column algorithm (left-looking, columns in order, each updated by the columns
  // before it in order) on the pattern's lists.
  const int* const below = below_.data();
  const Update* const updates = updates_.data();
  for (int j = 0; j < m; ++j) {
    double* cj = a + static_cast<long>(j) * m;
    for (int u = update_start_[j]; u < update_start_[j + 1]; ++u) {
      const Update& up = updates[u];
      const double* ck = a + static_cast<long>(up.k) * m;
      const double f = ck[j];
      if (f == 0) continue;
      for (int p = up.begin; p < up.end; ++p) cj[below[p]] -= f * ck[below[p]];
    }
    if (!(cj[j] > 0)) return false;
    const double d = std::sqrt(cj[j]);
    cj[j] = d;
    const double inv = 1 / d;
    for (int p = below_start_[j]; p < below_start_[j + 1]; ++p) cj[below[p]] *= inv;
  }
  return true;
}

void PatternCholesky::solve(const double* a, double* y) const {
  if (words(m_) == 1) {
    solve_on<1>(a, m_, col_.data(), y);
  } else {
    solve_on<2>(a, m_, col_.data(), y);
  }
}

// The pattern's bits as the lists factor() and solve() walk: a bit a step cost more than the
// arithmetic (a factor of 15 rows with 27 places took 3,000 instructions).
template <int W>
void PatternCholesky::lists(int m) {
  below_.clear();
  below_start_.assign(1, 0);
  for (int k = 0; k < m; ++k) {
    each<W>(col_.data() + static_cast<long>(k) * W, [&](int i) { below_.push_back(i); });
    below_start_.push_back(static_cast<int>(below_.size()));
  }
  // Column j is updated by each column k of its row, from row j (which column k holds) down.
  updates_.clear();
  update_start_.assign(1, 0);
  for (int j = 0; j < m; ++j) {
    each<W>(row_.data() + static_cast<long>(j) * W, [&](int k) {
      const int* const first = below_.data() + below_start_[k];
      const int* const last = below_.data() + below_start_[k + 1];
      const int begin = static_cast<int>(std::lower_bound(first, last, j) - below_.data());
      updates_.push_back({k, begin, below_start_[k + 1]});
    });
    update_start_.push_back(static_cast<int>(updates_.size()));
  }
}

}  // namespace dispcon
