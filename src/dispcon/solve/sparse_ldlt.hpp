// A sparse LDL^T (up-looking, entry by entry) of a symmetric matrix written in its elimination
// order, for the Newton polish's rows form J M^-1 J^T (polish_sparse.cpp). The arithmetic is
// that of Eigen's SimplicialLDLT, in the same order, so the factors and solutions are the same
// bits; what differs is the memory. Eigen's analysis copied the matrix twice (both triangles
// for an ordering it was not asked for, then the upper one permuted by nothing), and it
// allocated its factor and each factorisation's scratch afresh; on this machine the first touch
// of a 4 KB page costs about 16 us, so for a 100,000-link chain the memory cost more than the
// arithmetic. Here the matrix, its factor and the scratch are kept from one factorisation to
// the next, and those of 4 MB and more live on huge pages (huge_pages.hpp).
//
// No pivoting: the matrix must be positive definite (J M^-1 J^T + lambda I is) or at least
// have non-zero pivots in this order.
#pragma once

#include "dispcon/solve/huge_pages.hpp"

namespace dispcon {

class SparseLdlt {
 public:
  // A's upper triangle by columns, in elimination order: column c holds the rows
  // rows[starts[c]] ... rows[starts[c + 1] - 1], sorted, none past c, with values alike. The
  // caller lays out starts (n + 1 entries) and rows, then calls analyze(); it writes values
  // before each factorize().
  HugeVector<int> starts, rows;
  HugeVector<double> values;

  int size() const { return starts.empty() ? 0 : static_cast<int>(starts.size()) - 1; }
  // The factor's structure (the elimination tree and each column's count).
  void analyze();
  // A = L D L^T. False when a pivot is zero.
  bool factorize();
  // The right-hand side of the next solve(), n values (after analyze()): solve() leaves the
  // solution in its place.
  double* rhs() { return doubles_.data() + 2 * static_cast<size_t>(size()); }
  // Solves A x = b in place in rhs().
  void solve();

 private:
  // The values per unknown live in two buffers, so that a large system's reach huge pages
  // (each alone would stay under 4 MB): n + 1 ints of L's column starts (lp), then n each of the
  // elimination tree (parent), the entries of each column of L (count, filled so far while
  // factoring), factorize()'s row pattern and its marks (tags); n doubles each of D,
  // factorize()'s dense row (zero between uses) and the right-hand side.
  HugeVector<int> ints_;
  HugeVector<double> doubles_;
  // Where each of them begins (found anew in each call: the object may have been moved).
  struct Parts {
    int *lp, *parent, *count, *pattern, *tags;
    double *d, *y;
  };
  Parts parts();
  HugeVector<int> li_;  // L by columns, without its unit diagonal
  HugeVector<double> lx_;
};

}  // namespace dispcon
