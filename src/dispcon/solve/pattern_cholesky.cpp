#include "dispcon/solve/pattern_cholesky.hpp"

#include <cmath>
#include <cstdint>

namespace dispcon {

namespace {

// A set of rows 0 ... 64 kWords - 1, visited in increasing order. One word where it will do:
// the second word's loops cost more than the arithmetic in a system of 15 rows.
template <int kWords>
struct Rows {
  std::uint64_t w[kWords];  // not cleared here: only a system's own m rows are (see below)

  void add(int i) { w[i >> 6] |= std::uint64_t{1} << (i & 63); }
  int first() const {  // the smallest row (the set must not be empty)
    for (int h = 0;; ++h) {
      if (w[h]) return 64 * h + __builtin_ctzll(w[h]);
    }
  }
  bool empty() const {
    std::uint64_t any = 0;
    for (std::uint64_t x : w) any |= x;
    return any == 0;
  }
  // Adds the rows of `r` past row p (a child column's rows, to its parent p).
  void add_below(const Rows& r, int p) {
    for (int h = 0; h < kWords; ++h) {
      const int below = p - 64 * h;  // bits of word h up to row p are dropped
      const std::uint64_t keep = below < 0     ? ~std::uint64_t{0}
                                 : below >= 63 ? 0
                                               : ~std::uint64_t{0} << (below + 1);
      w[h] |= r.w[h] & keep;
    }
  }
  // f(i) for each row i >= from, in increasing order.
  template <typename F>
  void each_from(int from, F&& f) const {
    for (int h = from >> 6; h < kWords; ++h) {
      std::uint64_t bits = w[h];
      if (h == from >> 6) bits &= ~std::uint64_t{0} << (from & 63);
      for (; bits; bits &= bits - 1) f(64 * h + __builtin_ctzll(bits));
    }
  }
  template <typename F>
  void each(F&& f) const {
    each_from(0, f);
  }
};

template <int kWords>
bool solve_on_pattern(double* a, int m, double* y) {
  using Set = Rows<kWords>;
  // col[k]: the rows below the diagonal where column k of L may be non-zero: A's non-zero
  // places (a value that is not a number counts) and the fill, which column k passes to its
  // parent in the elimination tree (the first row below its diagonal). row[j]: the columns
  // k < j where row j of L may be non-zero, the columns that update column j.
  Set col[64 * kWords], row[64 * kWords];
  for (int k = 0; k < m; ++k) col[k] = row[k] = Set{};
  for (int k = 0; k < m; ++k) {
    const double* ck = a + static_cast<long>(k) * m;
    for (int i = k + 1; i < m; ++i) {
      if (ck[i] != 0) col[k].add(i);
    }
  }
  for (int k = 0; k < m; ++k) {
    if (col[k].empty()) continue;
    const int parent = col[k].first();
    col[parent].add_below(col[k], parent);
    col[k].each([&](int i) { row[i].add(k); });
  }
  // The dense column algorithm (left-looking, columns in order, each updated by the columns
  // before it in order) on the pattern.
  for (int j = 0; j < m; ++j) {
    double* cj = a + static_cast<long>(j) * m;
    row[j].each([&](int k) {
      const double* ck = a + static_cast<long>(k) * m;
      const double f = ck[j];
      if (f == 0) return;
      col[k].each_from(j, [&](int i) { cj[i] -= f * ck[i]; });
    });
    if (!(cj[j] > 0)) return false;
    const double d = std::sqrt(cj[j]);
    cj[j] = d;
    const double inv = 1 / d;
    col[j].each([&](int i) { cj[i] *= inv; });
  }
  for (int j = 0; j < m; ++j) {  // L z = b
    const double* cj = a + static_cast<long>(j) * m;
    y[j] /= cj[j];
    const double yj = y[j];
    col[j].each([&](int i) { y[i] -= yj * cj[i]; });
  }
  for (int j = m - 1; j >= 0; --j) {  // L^T y = z
    const double* cj = a + static_cast<long>(j) * m;
    double sum = y[j];
    col[j].each([&](int i) { sum -= cj[i] * y[i]; });
    y[j] = sum / cj[j];
  }
  return true;
}

}  // namespace

bool pattern_cholesky_solve(double* a, int m, double* y) {
  static_assert(kPatternRows == 128, "one or two words a column");
  return m <= 64 ? solve_on_pattern<1>(a, m, y) : solve_on_pattern<2>(a, m, y);
}

}  // namespace dispcon
