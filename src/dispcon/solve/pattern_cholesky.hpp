// The Cholesky of the Newton polish's small systems (polish_dense.cpp), worked only where its
// factor can be non-zero. Internal to the solver.
//
// A small group's J M^-1 J^T is mostly exact zeros: two rows couple only through a body they
// share, and a planar linkage posed in 3D splits each body's rows into in-plane ones (x, y, the
// turn about z) and out-of-plane ones (z, the two tilts) that share no component, so their
// products are exactly 0. In the 400 four-bars 27 of the factor's 105 places below the
// diagonal are non-zero; a dense Cholesky there spends most of its time testing and updating
// zeros. This one first finds the factor's pattern (the matrix's non-zero places and their
// fill), then does the dense column algorithm's operations on that pattern alone, in the same
// order: every value it writes has the same bits as the dense algorithm's (a place outside the
// pattern stays +0 there, and subtracting a product with +0 leaves a value as it was).
#pragma once

#include <cstdint>
#include <vector>

namespace dispcon {

// The most rows a PatternCholesky takes (two 64-bit words a column's pattern).
constexpr int kPatternRows = 128;

// The factorisation, with its pattern kept: the next system whose matrix has the same non-zero
// places (the group's next Newton step, or the next group of the same shape: the 400 four-bars
// have one pattern) skips finding the fill and the rows again, which cost a quarter of a
// factorisation of 15 rows. The pattern is compared whole, so a matrix with a place more or
// less is analysed anew: the values written are the same bits either way.
class PatternCholesky {
 public:
  // Factors a symmetric positive definite A of m <= kPatternRows rows given by its lower
  // triangle (column-major, m by m at `a`, overwritten by the factor L; the upper triangle is
  // not read). Returns false when a pivot is not positive.
  bool factor(double* a, int m);
  // Solves L L^T y = b in place (`y` holds b on entry) with the factor the last factor() that
  // succeeded left at `a`.
  void solve(const double* a, double* y) const;

 private:
  int m_ = -1;  // rows of the pattern kept (-1: none)
  // One or two words a column: given_ the matrix's non-zero places below the diagonal (a value
  // that is not a number counts), col_ those of L (with the fill), row_ the columns k < j where
  // row j of L may be non-zero (the columns that update column j).
  std::vector<std::uint64_t> given_, found_, col_, row_;
  // The pattern as lists for factor(): below_ holds each column's rows below the diagonal in order
  // (column k's from below_start_[k] to below_start_[k + 1]); updates_ each column's updates
  // (column j's from update_start_[j]): column k's rows below_[begin ... end), from row j down.
  struct Update {
    int k, begin, end;
  };
  template <int W>
  void lists(int m);
  std::vector<int> below_, below_start_, update_start_;
  std::vector<Update> updates_;
};

}  // namespace dispcon
