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
  // Solves A x = b in place (x holds b).
  void solve(double* x) const;

 private:
  HugeVector<int> parent_;   // the elimination tree
  HugeVector<int> count_;    // entries of each column of L (filled so far, while factoring)
  HugeVector<int> lp_, li_;  // L by columns, without its unit diagonal
  HugeVector<double> lx_, d_;
  HugeVector<double> y_;            // factorize()'s dense row, zero between uses
  HugeVector<int> pattern_, tags_;  // factorize()'s row pattern and marks
};

}  // namespace dispcon
