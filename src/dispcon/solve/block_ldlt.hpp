// A sparse LDL^T factorisation on 6 x 6 blocks, for the Newton polish's saddle-point systems
// (polish_blocks.cpp): each body's six unknowns make one block, each run of a joint's rows
// another (padded to six). Eigen's simplicial LDLT works entry by entry with an index per
// entry; here every operation is a fixed-size 6 x 6 product on contiguous memory, and the
// elimination order is found on the blocks (AMD), so the factor's structure is the blocks'.
//
// The matrix must be quasi-definite (as [-M J^T; J mu I] is): every pivot met in any order is
// then non-zero, so no pivoting is needed and the order is chosen for fill alone.
//
// The kernels keep a block's columns in vector registers, and the solve takes its columns
// level by level in the elimination tree (see solve()'s schedules below): a post-order makes
// each column wait for its child's last update, a chain of dependent operations the processor
// cannot overlap.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace dispcon {

class BlockLdlt {
 public:
  static constexpr int kSize = 6;
  static constexpr int kArea = kSize * kSize;  // a block's values, column-major
  // Where a block of A is stored: the lower triangle in elimination order holds A(i, j) or
  // its transpose.
  struct Slot {
    int index = -1;
    bool transposed = false;
  };

  // The pattern: `sizes[b]` unknowns in block b (1 to kSize), and the off-diagonal block pairs
  // (i, j) that may be non-zero (either triangle, repeats allowed). Finds the elimination
  // order, the factor's structure and where each update lands; allocates. A's values are then
  // written through slot() and at() after clear().
  void analyze(const std::vector<int>& sizes, const std::vector<std::pair<int, int>>& pairs);

  int blocks() const { return static_cast<int>(order_.size()); }
  // Blocks stored in the factor (diagonal ones included), for tests and figures.
  int stored_blocks() const { return static_cast<int>(row_.size()); }
  // Block (i, j) of A (i == j: the diagonal block, written whole, both triangles). The pair
  // must be in the pattern given to analyze().
  Slot slot(int i, int j) const;
  // Zeroes A, with 1 on the diagonal of the padding (the unknowns past a block's size), which
  // keeps the padding apart from everything else.
  void clear();
  double& at(Slot s, int r, int c) {
    return values_[static_cast<size_t>(kArea * s.index +
                                       (s.transposed ? kSize * r + c : kSize * c + r))];
  }
  // A = L D L^T in place. False when a pivot is zero or not finite.
  bool factorize();
  // Solves A x = b in place: x holds kSize values a block, block after block in the caller's
  // numbering (the padding's values must be 0, and stay 0).
  void solve(double* x);
  // The same without copies: the right-hand side is written, and the solution read, in place
  // through values_of(b), block b's kSize values (the padding's 0 as above), after
  // clear_values() zeroes them all.
  void clear_values();
  double* values_of(int b) { return z_.data() + kSize * pos_[static_cast<size_t>(b)]; }
  void solve();
  // The kernels' build factorize() and solve() run: x86-64's baseline, AVX2 (x86-64-v3), or
  // AVX-512 (v4, the wide one: a block's column of six in one vector of eight rather than four
  // and two). The widest the processor has is the default. They do the same operations in the
  // same order; tests compare them.
  enum class Kernel { kBase, kAvx2, kWide };
  static Kernel best_kernel();
  Kernel kernel() const { return kernel_; }
  // Takes `k` if the processor has it (and returns true); otherwise changes nothing.
  bool set_kernel(Kernel k);

 private:
  int slot_of(int a, int b) const;
  std::vector<int> sizes_;
  std::vector<int> order_;  // order_[k]: the caller's block eliminated k-th
  std::vector<int> pos_;    // pos_[b]: when the caller's block b is eliminated
  // The factor by columns (elimination order): column k's blocks are p = start_[k] ...
  // start_[k + 1] - 1, the diagonal first, then L's blocks in increasing row order; row_[p] is
  // block p's row, its values values_[kArea * p ...].
  std::vector<int> start_, row_;
  std::vector<double> values_;
  std::vector<double> pivots_;  // dk of each pivot block D = Lk dk Lk^T, kSize a block
  std::vector<int> targets_;    // where each update of factorize() lands, in its order
  // The solve's schedules (solve()): the forward substitution row by row, each row's blocks
  // gathered in column order (row_start_, row_block_, row_column_), the rows taken leaves
  // first by their height in the elimination tree (forward_); the back substitution column by
  // column, the root first by depth (back_). Columns of one level do not depend on each other,
  // so their chains of dependent operations overlap in the processor instead of waiting one
  // for the other as a post-order's parent and child do.
  std::vector<int> row_start_, row_block_, row_column_;
  std::vector<int> forward_, back_;
  Kernel kernel_ = best_kernel();
  std::vector<double> w_;  // a column's blocks times Lk^-T (before scaling by dk^-1)
  std::vector<double> z_;  // the solve's right-hand side in elimination order
};

}  // namespace dispcon
