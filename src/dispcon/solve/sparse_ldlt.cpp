#include "dispcon/solve/sparse_ldlt.hpp"

#include <cstddef>

namespace dispcon {

// Row k of L is the set of columns reached in the elimination tree from the entries of A's
// column k above the diagonal; each column's parent is the first row it meets.
void SparseLdlt::analyze() {
  const int n = size();
  const auto un = static_cast<size_t>(n);
  parent_.resize(un);
  count_.resize(un);
  tags_.resize(un);
  pattern_.resize(un);
  y_.assign(un, 0.0);
  d_.resize(un);
  for (int k = 0; k < n; ++k) {
    parent_[static_cast<size_t>(k)] = -1;
    tags_[static_cast<size_t>(k)] = k;
    count_[static_cast<size_t>(k)] = 0;
    for (int p = starts[static_cast<size_t>(k)]; p < starts[static_cast<size_t>(k) + 1]; ++p) {
      for (int i = rows[static_cast<size_t>(p)]; i < k && tags_[static_cast<size_t>(i)] != k;
           i = parent_[static_cast<size_t>(i)]) {
        if (parent_[static_cast<size_t>(i)] == -1) parent_[static_cast<size_t>(i)] = k;
        ++count_[static_cast<size_t>(i)];
        tags_[static_cast<size_t>(i)] = k;
      }
    }
  }
  lp_.resize(un + 1);
  lp_[0] = 0;
  for (size_t k = 0; k < un; ++k) lp_[k + 1] = lp_[k] + count_[k];
  li_.resize(static_cast<size_t>(lp_[un]));
  lx_.resize(static_cast<size_t>(lp_[un]));
}

// Row by row: row k of L solves L(0:k, 0:k) D l = A(0:k, k) over the pattern found in the
// elimination tree (in topological order), and D(k) is what is left of A(k, k).
bool SparseLdlt::factorize() {
  const int n = size();
  for (int k = 0; k < n; ++k) {
    y_[static_cast<size_t>(k)] = 0;
    int top = n;
    tags_[static_cast<size_t>(k)] = k;
    count_[static_cast<size_t>(k)] = 0;
    for (int p = starts[static_cast<size_t>(k)]; p < starts[static_cast<size_t>(k) + 1]; ++p) {
      int i = rows[static_cast<size_t>(p)];
      y_[static_cast<size_t>(i)] += values[static_cast<size_t>(p)];
      int len = 0;
      for (; tags_[static_cast<size_t>(i)] != k; i = parent_[static_cast<size_t>(i)]) {
        pattern_[static_cast<size_t>(len++)] = i;
        tags_[static_cast<size_t>(i)] = k;
      }
      while (len > 0) pattern_[static_cast<size_t>(--top)] = pattern_[static_cast<size_t>(--len)];
    }
    double d = y_[static_cast<size_t>(k)];
    y_[static_cast<size_t>(k)] = 0;
    for (; top < n; ++top) {
      const auto i = static_cast<size_t>(pattern_[static_cast<size_t>(top)]);
      const double yi = y_[i];
      y_[i] = 0;
      const double l = yi / d_[i];
      const int end = lp_[i] + count_[i];
      int p = lp_[i];
      for (; p < end; ++p)
        y_[static_cast<size_t>(li_[static_cast<size_t>(p)])] -= lx_[static_cast<size_t>(p)] * yi;
      d -= l * yi;
      li_[static_cast<size_t>(p)] = k;
      lx_[static_cast<size_t>(p)] = l;
      ++count_[i];
    }
    d_[static_cast<size_t>(k)] = d;
    if (d == 0) return false;
  }
  return true;
}

void SparseLdlt::solve(double* x) const {
  const int n = size();
  for (int j = 0; j < n; ++j) {  // L z = b
    const double t = x[j];
    if (t == 0) continue;
    for (int p = lp_[static_cast<size_t>(j)]; p < lp_[static_cast<size_t>(j) + 1]; ++p) {
      x[li_[static_cast<size_t>(p)]] -= t * lx_[static_cast<size_t>(p)];
    }
  }
  for (int j = 0; j < n; ++j) x[j] = (1 / d_[static_cast<size_t>(j)]) * x[j];  // D w = z
  for (int j = n - 1; j >= 0; --j) {                                           // L^T x = w
    double t = x[j];
    for (int p = lp_[static_cast<size_t>(j)]; p < lp_[static_cast<size_t>(j) + 1]; ++p) {
      t -= lx_[static_cast<size_t>(p)] * x[li_[static_cast<size_t>(p)]];
    }
    x[j] = t;
  }
}

}  // namespace dispcon
