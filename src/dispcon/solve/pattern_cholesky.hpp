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

namespace dispcon {

// The most rows pattern_cholesky_solve() takes (two 64-bit words a column's pattern).
constexpr int kPatternRows = 128;

// Solves A y = b in place for a symmetric positive definite A of m <= kPatternRows rows given by
// its lower triangle (column-major, m by m at `a`, overwritten by the factor L; the upper
// triangle is not read); `y` holds b on entry. Returns false when a pivot is not positive.
bool pattern_cholesky_solve(double* a, int m, double* y);

}  // namespace dispcon
