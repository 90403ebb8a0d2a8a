#include "dispcon/solve/sparse_ldlt.hpp"

#include <cstddef>

namespace dispcon {

SparseLdlt::Parts SparseLdlt::parts() {
  const auto n = static_cast<size_t>(size());
  Parts p;
  p.lp = ints_.data();
  p.parent = p.lp + n + 1;
  p.count = p.parent + n;
  p.pattern = p.count + n;
  p.tags = p.pattern + n;
  p.d = doubles_.data();
  p.y = p.d + n;
  return p;
}

// Row k of L is the set of columns reached in the elimination tree from the entries of A's
// column k above the diagonal; each column's parent is the first row it meets.
void SparseLdlt::analyze() {
  const int n = size();
  ints_.resize(5 * static_cast<size_t>(n) + 1);
  doubles_.assign(3 * static_cast<size_t>(n), 0.0);
  const Parts w = parts();
  const int* const start = starts.data();
  const int* const row = rows.data();
  for (int k = 0; k < n; ++k) {
    w.parent[k] = -1;
    w.tags[k] = k;
    w.count[k] = 0;
    for (int p = start[k]; p < start[k + 1]; ++p) {
      for (int i = row[p]; w.tags[i] != k; i = w.parent[i]) {
        if (w.parent[i] == -1) w.parent[i] = k;
        ++w.count[i];
        w.tags[i] = k;
      }
    }
  }
  w.lp[0] = 0;
  for (int k = 0; k < n; ++k) w.lp[k + 1] = w.lp[k] + w.count[k];
  li_.resize(static_cast<size_t>(w.lp[n]));
  lx_.resize(static_cast<size_t>(w.lp[n]));
}

// Row by row: row k of L solves L(0:k, 0:k) D l = A(0:k, k) over the pattern found in the
// elimination tree (in topological order), and D(k) is what is left of A(k, k).
bool SparseLdlt::factorize() {
  const int n = size();
  const Parts w = parts();
  const int* const start = starts.data();
  const int* const row = rows.data();
  const double* const value = values.data();
  int* const li = li_.data();
  double* const lx = lx_.data();
  for (int k = 0; k < n; ++k) {
    w.y[k] = 0;
    int top = n;
    w.tags[k] = k;
    w.count[k] = 0;
    for (int p = start[k]; p < start[k + 1]; ++p) {
      int i = row[p];
      w.y[i] += value[p];
      int len = 0;
      for (; w.tags[i] != k; i = w.parent[i]) {
        w.pattern[len++] = i;
        w.tags[i] = k;
      }
      while (len > 0) w.pattern[--top] = w.pattern[--len];
    }
    double d = w.y[k];
    w.y[k] = 0;
    for (; top < n; ++top) {
      const int i = w.pattern[top];
      const double yi = w.y[i];
      w.y[i] = 0;
      const double l = yi / w.d[i];
      const int end = w.lp[i] + w.count[i];
      int p = w.lp[i];
      for (; p < end; ++p) w.y[li[p]] -= lx[p] * yi;
      d -= l * yi;
      li[p] = k;
      lx[p] = l;
      ++w.count[i];
    }
    w.d[k] = d;
    if (d == 0) return false;
  }
  return true;
}

void SparseLdlt::solve() {
  const int n = size();
  const Parts w = parts();
  double* const x = rhs();
  const int* const li = li_.data();
  const double* const lx = lx_.data();
  for (int j = 0; j < n; ++j) {  // L z = b
    const double t = x[j];
    if (t == 0) continue;
    for (int p = w.lp[j]; p < w.lp[j + 1]; ++p) x[li[p]] -= t * lx[p];
  }
  for (int j = 0; j < n; ++j) x[j] = (1 / w.d[j]) * x[j];  // D w = z
  for (int j = n - 1; j >= 0; --j) {                       // L^T x = w
    double t = x[j];
    for (int p = w.lp[j]; p < w.lp[j + 1]; ++p) t -= lx[p] * x[li[p]];
    x[j] = t;
  }
}

}  // namespace dispcon
