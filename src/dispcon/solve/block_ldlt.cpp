#include "dispcon/solve/block_ldlt.hpp"

#include <Eigen/OrderingMethods>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>
// glibc's CPU_FEATURE_ACTIVE, for GCC only (the kernels below are GCC's): the header's inline
// functions return C's _Bool, which g++ takes and clang++ refuses (the fuzz targets' build).
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__) && \
    __has_include(<sys/platform/x86.h>)
#include <sys/platform/x86.h>
#endif

namespace dispcon {

// Column k of the factor holds the blocks of rows struct(k): A's non-zero blocks below the
// diagonal in column k, and every row of a column eliminated earlier whose first row (its
// parent in the elimination tree) is k. The update of column k, A_ab -= L_ak D_k L_bk^T for
// every pair of rows a >= b in struct(k), lands in column b at row a, which is there by the
// same rule; targets_ lists those places once, so factorize() only multiplies.
void BlockLdlt::analyze(const std::vector<int>& sizes,
                        const std::vector<std::pair<int, int>>& pairs) {
  const int n = static_cast<int>(sizes.size());
  for (int s : sizes) {
    if (s < 1 || s > kSize) throw std::invalid_argument("BlockLdlt: block size out of range");
  }
  sizes_ = sizes;
  // Fill-reducing order of the blocks (Eigen's orderings return the inverse permutation: the
  // k-th index is the k-th block to eliminate).
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(pairs.size() + static_cast<size_t>(n));
  for (int b = 0; b < n; ++b) triplets.emplace_back(b, b, 1.0);
  for (const auto& [i, j] : pairs) triplets.emplace_back(std::max(i, j), std::min(i, j), 1.0);
  Eigen::SparseMatrix<double> lower(n, n);
  lower.setFromTriplets(triplets.begin(), triplets.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
  Eigen::AMDOrdering<int>()(lower.selfadjointView<Eigen::Lower>(), inverse);
  order_.assign(inverse.indices().data(), inverse.indices().data() + n);
  pos_.assign(static_cast<size_t>(n), 0);
  for (int k = 0; k < n; ++k) pos_[static_cast<size_t>(order_[static_cast<size_t>(k)])] = k;

  // The factor's structure, column by column: A's rows, then the children's.
  std::vector<std::vector<int>> below(static_cast<size_t>(n)), children(static_cast<size_t>(n));
  for (const auto& [i, j] : pairs) {
    const int a = pos_[static_cast<size_t>(i)], b = pos_[static_cast<size_t>(j)];
    if (a != b) below[static_cast<size_t>(std::min(a, b))].push_back(std::max(a, b));
  }
  std::vector<int> mark(static_cast<size_t>(n), -1);
  start_.assign(1, 0);
  row_.clear();
  for (int k = 0; k < n; ++k) {
    const size_t first = row_.size();
    row_.push_back(k);
    mark[static_cast<size_t>(k)] = k;
    auto add = [&](int i) {
      if (mark[static_cast<size_t>(i)] != k) {
        mark[static_cast<size_t>(i)] = k;
        row_.push_back(i);
      }
    };
    for (int i : below[static_cast<size_t>(k)]) add(i);
    for (int c : children[static_cast<size_t>(k)]) {
      for (int p = start_[static_cast<size_t>(c)] + 1; p < start_[static_cast<size_t>(c) + 1];
           ++p) {
        add(row_[static_cast<size_t>(p)]);
      }
    }
    std::sort(row_.begin() + static_cast<std::ptrdiff_t>(first) + 1, row_.end());
    if (row_.size() > first + 1) children[static_cast<size_t>(row_[first + 1])].push_back(k);
    start_.push_back(static_cast<int>(row_.size()));
  }
  // Two values past the end: the wide solve reads a column of six as a vector of eight.
  values_.assign(kArea * row_.size() + 2, 0.0);
  pivots_.assign(static_cast<size_t>(kSize * n), 0.0);
  z_.assign(static_cast<size_t>(kSize * n) + 2, 0.0);

  // Where each update lands.
  targets_.clear();
  size_t widest = 0;
  for (int k = 0; k < n; ++k) {
    const int begin = start_[static_cast<size_t>(k)] + 1, end = start_[static_cast<size_t>(k) + 1];
    widest = std::max(widest, static_cast<size_t>(end - begin));
    for (int a = begin; a < end; ++a) {
      for (int b = begin; b <= a; ++b) {
        targets_.push_back(slot_of(row_[static_cast<size_t>(a)], row_[static_cast<size_t>(b)]));
      }
    }
  }
  w_.assign(kArea * widest + 2, 0.0);  // two more: the wide kernel stores eight

  // The solve's schedules: each column's parent is its first row below the diagonal.
  std::vector<int> height(static_cast<size_t>(n), 0), depth(static_cast<size_t>(n), 0);
  std::vector<int> parent(static_cast<size_t>(n), -1);
  row_start_.assign(static_cast<size_t>(n) + 1, 0);
  for (int k = 0; k < n; ++k) {
    const int begin = start_[static_cast<size_t>(k)] + 1, end = start_[static_cast<size_t>(k) + 1];
    if (begin < end) {
      const int p = row_[static_cast<size_t>(begin)];
      parent[static_cast<size_t>(k)] = p;
      height[static_cast<size_t>(p)] =
          std::max(height[static_cast<size_t>(p)], height[static_cast<size_t>(k)] + 1);
    }
    for (int q = begin; q < end; ++q)
      ++row_start_[static_cast<size_t>(row_[static_cast<size_t>(q)]) + 1];
  }
  for (int k = n - 1; k >= 0; --k) {
    const int p = parent[static_cast<size_t>(k)];
    if (p >= 0) depth[static_cast<size_t>(k)] = depth[static_cast<size_t>(p)] + 1;
  }
  for (int k = 0; k < n; ++k)
    row_start_[static_cast<size_t>(k) + 1] += row_start_[static_cast<size_t>(k)];
  row_block_.resize(static_cast<size_t>(row_start_.back()));
  row_column_.resize(row_block_.size());
  std::vector<int> next(row_start_.begin(), row_start_.end() - 1);
  for (int k = 0; k < n; ++k) {  // columns in increasing order: each row's blocks in that order
    for (int q = start_[static_cast<size_t>(k)] + 1; q < start_[static_cast<size_t>(k) + 1]; ++q) {
      const int at = next[static_cast<size_t>(row_[static_cast<size_t>(q)])]++;
      row_block_[static_cast<size_t>(at)] = q;
      row_column_[static_cast<size_t>(at)] = k;
    }
  }
  auto by_level = [n](const std::vector<int>& level, std::vector<int>& out) {
    out.resize(static_cast<size_t>(n));
    for (int k = 0; k < n; ++k) out[static_cast<size_t>(k)] = k;
    std::stable_sort(out.begin(), out.end(), [&](int a, int b) {
      return level[static_cast<size_t>(a)] < level[static_cast<size_t>(b)];
    });
  };
  by_level(height, forward_);
  by_level(depth, back_);
}

// Index of the stored block at row a of column b (elimination order, a >= b).
int BlockLdlt::slot_of(int a, int b) const {
  const auto first = row_.begin() + start_[static_cast<size_t>(b)];
  const auto last = row_.begin() + start_[static_cast<size_t>(b) + 1];
  const auto it = std::lower_bound(first, last, a);
  if (it == last || *it != a) throw std::logic_error("BlockLdlt: block outside the pattern");
  return static_cast<int>(it - row_.begin());
}

BlockLdlt::Slot BlockLdlt::slot(int i, int j) const {
  const int a = pos_[static_cast<size_t>(i)], b = pos_[static_cast<size_t>(j)];
  return a >= b ? Slot{slot_of(a, b), false} : Slot{slot_of(b, a), true};
}

void BlockLdlt::clear() {
  std::fill(values_.begin(), values_.end(), 0.0);
  for (int k = 0; k < blocks(); ++k) {
    double* d = values_.data() + kArea * start_[static_cast<size_t>(k)];
    for (int i = sizes_[static_cast<size_t>(order_[static_cast<size_t>(k)])]; i < kSize; ++i) {
      d[kSize * i + i] = 1;
    }
  }
}

namespace {

constexpr int kSize = BlockLdlt::kSize, kArea = BlockLdlt::kArea;

// The kernels below run over every block of the factor; on x86-64 they are also compiled for
// AVX2 and for AVX-512 (the "wide" ones), and BlockLdlt calls the widest the processor has (the
// same arithmetic in the same order, so the same bits). Measured on the 105-link grid's drag
// (Zen 5, AVX-512 on full-width units): the factorisation 131 -> 62-79 us, a solve 12.6 -> 10.0
// us, the same bits. Separate functions chosen where a BlockLdlt is made, not GCC's
// target_clones: those link in libgcc's processor check, a constructor that runs the cpuid
// instruction 10 times at every start of every program (about 7 us each on a VM, where it
// traps), drags or not; glibc has already asked the processor once, and says what it found.
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define DISPCON_AVX2 __attribute__((target("arch=x86-64-v3")))
#define DISPCON_WIDE 1
#endif

// The solve's block products on a block's columns split 4 + 2 (GCC's vector types: AVX2 in that
// clone, pairs of SSE2 operations in the default one, the same operations on every entry):
// plain loops kept z in memory between columns, a chain of store forwardings, and the
// transposed product gathered each column's entries across the block.
#if defined(__GNUC__)
#define DISPCON_VECTORS 1
using V4 = double __attribute__((vector_size(32)));
using V2 = double __attribute__((vector_size(16)));
using V8 = double __attribute__((vector_size(64)));
// Unaligned loads and stores (by reference: a vector passed by value changes the default
// clone's ABI).
template <typename V>
inline void load(V& v, const double* p) {
  std::memcpy(&v, p, sizeof v);
}
template <typename V>
inline void store(double* p, const V& v) {
  std::memcpy(p, &v, sizeof v);
}
#endif

// Factors the pivot block d = Lk dk Lk^T in place (Lk below the diagonal, dk in `pivot`),
// without pivoting, as an entry-by-entry LDL^T would.
bool factor_pivot(double* d, double* pivot) {
  auto at = [d](int i, int j) -> double& { return d[kSize * j + i]; };
  for (int j = 0; j < kSize; ++j) {
    double s = at(j, j);
    for (int p = 0; p < j; ++p) s -= at(j, p) * at(j, p) * pivot[p];
    if (!(std::abs(s) > 0) || !std::isfinite(s)) return false;
    pivot[j] = s;
    for (int i = j + 1; i < kSize; ++i) {
      double v = at(i, j);
      for (int p = 0; p < j; ++p) v -= at(i, p) * at(j, p) * pivot[p];
      at(i, j) = v / s;
    }
  }
  return true;
}

// Right-looking, in the scalar LDL^T's arithmetic: column k's pivot block is final once the
// columns before it are eliminated, and is factored D = Lk dk Lk^T. Its blocks W_ak become
// Y_ak = W_ak Lk^-T and L_ak = Y_ak dk^-1 (the factor's entries), and update the blocks they
// meet, A_ab -= L_ak Y_bk^T. An explicit inverse of D would be quicker to apply but is not
// stable: where a joint's rows were eliminated before its bodies the body's pivot is
// -M - J^T J / mu, with mu as small as 1e-12 of J M^-1 J^T, and its inverse is good to a few
// digits only, which the next products multiply by 1/mu.
template <bool Wide>
__attribute__((always_inline)) inline bool factor_kernel(int n, const int* start,
                                                         const int* targets, double* values,
                                                         double* pivots, double* y) {
  for (int k = 0; k < n; ++k) {
    double* d = values + kArea * start[k];
    double* dk = pivots + kSize * k;
    if (!factor_pivot(d, dk)) return false;
    double inverse[kSize];
    for (int i = 0; i < kSize; ++i) inverse[i] = 1 / dk[i];
    const int count = start[k + 1] - start[k] - 1;
    double* column = d + kArea;
#ifdef DISPCON_VECTORS
    // The same operations on each entry in the same order as the loops below, with a block's
    // columns held in registers rather than stored and loaded again after every product. Wide:
    // a column of six in a vector of eight, as in the solve; only six are stored into the
    // factor (the scratch y is padded for the eight).
    if constexpr (Wide) {
      for (int q = 0; q < count; ++q) {
        double* l = column + kArea * q;
        double* yq = y + kArea * q;
        V8 y8[kSize];
        for (int j = 0; j < kSize; ++j) {  // Y Lk^T = W, column by column
          load(y8[j], l + kSize * j);
          for (int p = 0; p < j; ++p) y8[j] -= y8[p] * d[kSize * p + j];
          store(yq + kSize * j, y8[j]);
          const V8 lj = y8[j] * inverse[j];
          store(l + kSize * j, V4{lj[0], lj[1], lj[2], lj[3]});
          store(l + kSize * j + 4, V2{lj[4], lj[5]});
        }
      }
      for (int a = 0; a < count; ++a) {
        const double* la = column + kArea * a;
        V8 l8[kSize];
        for (int q = 0; q < kSize; ++q) load(l8[q], la + kSize * q);
        for (int b = 0; b <= a; ++b) {  // A_ab -= L_a Y_b^T
          const double* yb = y + kArea * b;
          double* t = values + kArea * *targets++;
          for (int c = 0; c < kSize; ++c) {
            V8 t8;
            load(t8, t + kSize * c);
            for (int q = 0; q < kSize; ++q) t8 -= l8[q] * yb[kSize * q + c];
            store(t + kSize * c, V4{t8[0], t8[1], t8[2], t8[3]});
            store(t + kSize * c + 4, V2{t8[4], t8[5]});
          }
        }
      }
      continue;
    }
    for (int q = 0; q < count; ++q) {
      double* l = column + kArea * q;
      double* yq = y + kArea * q;
      V4 y4[kSize];
      V2 y2[kSize];
      for (int j = 0; j < kSize; ++j) {  // Y Lk^T = W, column by column
        load(y4[j], l + kSize * j);
        load(y2[j], l + kSize * j + 4);
        for (int p = 0; p < j; ++p) {
          const double f = d[kSize * p + j];
          y4[j] -= y4[p] * (V4{1, 1, 1, 1} * f);
          y2[j] -= y2[p] * (V2{1, 1} * f);
        }
        store(yq + kSize * j, y4[j]);
        store(yq + kSize * j + 4, y2[j]);
        store(l + kSize * j, y4[j] * (V4{1, 1, 1, 1} * inverse[j]));
        store(l + kSize * j + 4, y2[j] * (V2{1, 1} * inverse[j]));
      }
    }
    for (int a = 0; a < count; ++a) {
      const double* la = column + kArea * a;
      V4 l4[kSize];
      V2 l2[kSize];
      for (int q = 0; q < kSize; ++q) {
        load(l4[q], la + kSize * q);
        load(l2[q], la + kSize * q + 4);
      }
      for (int b = 0; b <= a; ++b) {  // A_ab -= L_a Y_b^T
        const double* yb = y + kArea * b;
        double* t = values + kArea * *targets++;
        for (int c = 0; c < kSize; ++c) {
          V4 t4;
          V2 t2;
          load(t4, t + kSize * c);
          load(t2, t + kSize * c + 4);
          for (int q = 0; q < kSize; ++q) {
            const double f = yb[kSize * q + c];
            t4 -= l4[q] * (V4{1, 1, 1, 1} * f);
            t2 -= l2[q] * (V2{1, 1} * f);
          }
          store(t + kSize * c, t4);
          store(t + kSize * c + 4, t2);
        }
      }
    }
#else
    for (int q = 0; q < count; ++q) {
      double* l = column + kArea * q;
      double* yq = y + kArea * q;
      for (int j = 0; j < kSize; ++j) {  // Y Lk^T = W, column by column
        double* yj = yq + kSize * j;
        for (int i = 0; i < kSize; ++i) yj[i] = l[kSize * j + i];
        for (int p = 0; p < j; ++p) {
          const double f = d[kSize * p + j];
          const double* yp = yq + kSize * p;
          for (int i = 0; i < kSize; ++i) yj[i] -= f * yp[i];
        }
        for (int i = 0; i < kSize; ++i) l[kSize * j + i] = yj[i] * inverse[j];
      }
    }
    for (int a = 0; a < count; ++a) {
      const double* la = column + kArea * a;
      for (int b = 0; b <= a; ++b) {  // A_ab -= L_a Y_b^T
        const double* yb = y + kArea * b;
        double* t = values + kArea * *targets++;
        for (int c = 0; c < kSize; ++c) {
          for (int q = 0; q < kSize; ++q) {
            const double f = yb[kSize * q + c];
            for (int i = 0; i < kSize; ++i) t[kSize * c + i] -= la[kSize * q + i] * f;
          }
        }
      }
    }
#endif
  }
  return true;
}

bool factor_columns(int n, const int* start, const int* targets, double* values, double* pivots,
                    double* y) {
  return factor_kernel<false>(n, start, targets, values, pivots, y);
}

#ifdef DISPCON_WIDE
DISPCON_AVX2 bool factor_columns_avx2(int n, const int* start, const int* targets, double* values,
                                      double* pivots, double* y) {
  return factor_kernel<false>(n, start, targets, values, pivots, y);
}

__attribute__((target("arch=x86-64-v4"))) bool factor_columns_wide(int n, const int* start,
                                                                   const int* targets,
                                                                   double* values, double* pivots,
                                                                   double* y) {
  return factor_kernel<true>(n, start, targets, values, pivots, y);
}
#endif

// Lk z = z and Lk^T z = z for a pivot's unit lower triangle, unrolled in registers (as loops,
// the compiler vectorised the short inner runs with a tail each, and z went through memory).
inline void lower_solve(const double* __restrict l, double* __restrict z) {
  double t[kSize];
  for (int i = 0; i < kSize; ++i) t[i] = z[i];
#pragma GCC unroll 6
  for (int j = 0; j < kSize; ++j) {
#pragma GCC unroll 6
    for (int i = j + 1; i < kSize; ++i) t[i] -= l[kSize * j + i] * t[j];
  }
  for (int i = 0; i < kSize; ++i) z[i] = t[i];
}
inline void upper_solve(const double* __restrict l, double* __restrict z) {
  double t[kSize];
  for (int i = 0; i < kSize; ++i) t[i] = z[i];
#pragma GCC unroll 6
  for (int j = kSize - 2; j >= 0; --j) {
#pragma GCC unroll 6
    for (int i = j + 1; i < kSize; ++i) t[j] -= l[kSize * j + i] * t[i];
  }
  for (int i = 0; i < kSize; ++i) z[i] = t[i];
}

// L z = b, then D, then L^T x = z, where L's diagonal blocks are the pivots' Lk. Forward, row
// by row: z_k -= sum_c L_kc z_c over the row's blocks in column order (the very operations, in
// the same order, that pushing each column's products into the rows below makes), then Lk.
// Back, z_k -= sum_p L_p^T z_(row p): the products are summed entry by entry over the column's
// blocks and each of the six sums reduced once at the end, rather than a dot product per column
// of every block. Both take their rows or columns level by level (BlockLdlt's schedules).
// Wide: a block's column of six in one vector of eight (AVX-512), whose last two lanes read
// the next column's first entries (or the buffers' padding) and are never stored nor summed.
template <bool Wide>
__attribute__((always_inline)) inline void solve_kernel(int n, const int* start, const int* row,
                                                        const int* row_start, const int* row_block,
                                                        const int* row_column, const int* forward,
                                                        const int* back, const double* values,
                                                        const double* pivots, double* z) {
  for (int s = 0; s < n; ++s) {
    const int k = forward[s];
    double* zk = z + kSize * k;
#ifdef DISPCON_VECTORS
    if constexpr (Wide) {
      V8 a, l;
      load(a, zk);
      for (int e = row_start[k]; e < row_start[k + 1]; ++e) {
        const double* lb = values + kArea * row_block[e];
        const double* x = z + kSize * row_column[e];
        for (int j = 0; j < kSize; ++j) {
          load(l, lb + kSize * j);
          a -= l * x[j];
        }
      }
      store(zk, V4{a[0], a[1], a[2], a[3]});
      store(zk + 4, V2{a[4], a[5]});
    } else {
      V4 a, la;
      V2 b, lb;
      load(a, zk);
      load(b, zk + 4);
      for (int e = row_start[k]; e < row_start[k + 1]; ++e) {
        const double* l = values + kArea * row_block[e];
        const double* x = z + kSize * row_column[e];
        for (int j = 0; j < kSize; ++j) {
          load(la, l + kSize * j);
          load(lb, l + kSize * j + 4);
          a -= la * (V4{1, 1, 1, 1} * x[j]);  // broadcasts (times 1: exact, a zero's sign too)
          b -= lb * (V2{1, 1} * x[j]);
        }
      }
      store(zk, a);
      store(zk + 4, b);
    }
#else
    for (int e = row_start[k]; e < row_start[k + 1]; ++e) {
      const double* l = values + kArea * row_block[e];
      const double* x = z + kSize * row_column[e];
      for (int j = 0; j < kSize; ++j) {
        for (int i = 0; i < kSize; ++i) zk[i] -= l[kSize * j + i] * x[j];
      }
    }
#endif
    lower_solve(values + kArea * start[k], zk);
  }
  for (int s = 0; s < n; ++s) {
    const int k = back[s];
    double* zk = z + kSize * k;
    for (int i = 0; i < kSize; ++i) zk[i] /= pivots[kSize * k + i];
    double sum[kSize];
#ifdef DISPCON_VECTORS
    if constexpr (Wide) {
      V8 a[kSize] = {};
      for (int p = start[k] + 1; p < start[k + 1]; ++p) {
        const double* l = values + kArea * p;
        V8 x, lj;
        load(x, z + kSize * row[p]);
        for (int j = 0; j < kSize; ++j) {
          load(lj, l + kSize * j);
          a[j] += lj * x;
        }
      }
      for (int j = 0; j < kSize; ++j)
        sum[j] = a[j][0] + a[j][1] + a[j][2] + a[j][3] + a[j][4] + a[j][5];
    } else {
      V4 a[kSize] = {};
      V2 b[kSize] = {};
      for (int p = start[k] + 1; p < start[k + 1]; ++p) {
        const double* l = values + kArea * p;
        const double* x = z + kSize * row[p];
        V4 x4, la;
        V2 x2, lb;
        load(x4, x);
        load(x2, x + 4);
        for (int j = 0; j < kSize; ++j) {
          load(la, l + kSize * j);
          load(lb, l + kSize * j + 4);
          a[j] += la * x4;
          b[j] += lb * x2;
        }
      }
      for (int j = 0; j < kSize; ++j)
        sum[j] = a[j][0] + a[j][1] + a[j][2] + a[j][3] + b[j][0] + b[j][1];
    }
#else
    double acc[kArea] = {};
    for (int p = start[k] + 1; p < start[k + 1]; ++p) {
      const double* l = values + kArea * p;
      const double* x = z + kSize * row[p];
      for (int j = 0; j < kSize; ++j) {
        for (int i = 0; i < kSize; ++i) acc[kSize * j + i] += l[kSize * j + i] * x[i];
      }
    }
    for (int j = 0; j < kSize; ++j) {
      sum[j] = acc[kSize * j] + acc[kSize * j + 1] + acc[kSize * j + 2] + acc[kSize * j + 3] +
               acc[kSize * j + 4] + acc[kSize * j + 5];
    }
#endif
    for (int j = 0; j < kSize; ++j) zk[j] -= sum[j];
    upper_solve(values + kArea * start[k], zk);
  }
}

void solve_columns(int n, const int* start, const int* row, const int* row_start,
                   const int* row_block, const int* row_column, const int* forward, const int* back,
                   const double* values, const double* pivots, double* z) {
  solve_kernel<false>(n, start, row, row_start, row_block, row_column, forward, back, values,
                      pivots, z);
}

#ifdef DISPCON_WIDE
DISPCON_AVX2 void solve_columns_avx2(int n, const int* start, const int* row, const int* row_start,
                                     const int* row_block, const int* row_column,
                                     const int* forward, const int* back, const double* values,
                                     const double* pivots, double* z) {
  solve_kernel<false>(n, start, row, row_start, row_block, row_column, forward, back, values,
                      pivots, z);
}

__attribute__((target("arch=x86-64-v4"))) void solve_columns_wide(
    int n, const int* start, const int* row, const int* row_start, const int* row_block,
    const int* row_column, const int* forward, const int* back, const double* values,
    const double* pivots, double* z) {
  solve_kernel<true>(n, start, row, row_start, row_block, row_column, forward, back, values, pivots,
                     z);
}
#endif

}  // namespace

// What the processor and the system let the kernels use: x86-64-v3 (AVX2, FMA, BMI1/2, F16C,
// LZCNT, MOVBE, and the system saving the YMM registers) and x86-64-v4 (AVX-512 F, BW, CD, DQ,
// VL, and the ZMM registers saved), as GCC's target names define them. glibc's answer (2.33 and
// later) is what its start found, read from its memory: no cpuid here.
BlockLdlt::Kernel BlockLdlt::best_kernel() {
#if defined(DISPCON_WIDE) && __has_include(<sys/platform/x86.h>)
  const bool v3 = CPU_FEATURE_ACTIVE(AVX) && CPU_FEATURE_ACTIVE(AVX2) && CPU_FEATURE_ACTIVE(BMI1) &&
                  CPU_FEATURE_ACTIVE(BMI2) && CPU_FEATURE_ACTIVE(F16C) && CPU_FEATURE_ACTIVE(FMA) &&
                  CPU_FEATURE_ACTIVE(LZCNT) && CPU_FEATURE_ACTIVE(MOVBE) &&
                  CPU_FEATURE_ACTIVE(OSXSAVE);
  const bool v4 = v3 && CPU_FEATURE_ACTIVE(AVX512F) && CPU_FEATURE_ACTIVE(AVX512BW) &&
                  CPU_FEATURE_ACTIVE(AVX512CD) && CPU_FEATURE_ACTIVE(AVX512DQ) &&
                  CPU_FEATURE_ACTIVE(AVX512VL);
  return v4 ? Kernel::kWide : v3 ? Kernel::kAvx2 : Kernel::kBase;
#elif defined(DISPCON_WIDE)
  return __builtin_cpu_supports("x86-64-v4") ? Kernel::kWide
         : __builtin_cpu_supports("x86-64-v3") ? Kernel::kAvx2
                                               : Kernel::kBase;
#else
  return Kernel::kBase;
#endif
}

bool BlockLdlt::set_kernel(Kernel k) {
  if (static_cast<int>(k) > static_cast<int>(best_kernel())) return false;
  kernel_ = k;
  return true;
}

bool BlockLdlt::factorize() {
#ifdef DISPCON_WIDE
  if (kernel_ == Kernel::kWide) {
    return factor_columns_wide(blocks(), start_.data(), targets_.data(), values_.data(),
                               pivots_.data(), w_.data());
  }
  if (kernel_ == Kernel::kAvx2) {
    return factor_columns_avx2(blocks(), start_.data(), targets_.data(), values_.data(),
                               pivots_.data(), w_.data());
  }
#endif
  return factor_columns(blocks(), start_.data(), targets_.data(), values_.data(), pivots_.data(),
                        w_.data());
}

void BlockLdlt::solve(double* x) {
  const int n = blocks();
  for (int b = 0; b < n; ++b) std::copy_n(x + kSize * b, kSize, values_of(b));
  solve();
  for (int b = 0; b < n; ++b) std::copy_n(values_of(b), kSize, x + kSize * b);
}

void BlockLdlt::clear_values() {
  std::fill(z_.begin(), z_.end(), 0.0);
}

void BlockLdlt::solve() {
  const int n = blocks();
#ifdef DISPCON_WIDE
  if (kernel_ == Kernel::kWide) {
    solve_columns_wide(n, start_.data(), row_.data(), row_start_.data(), row_block_.data(),
                       row_column_.data(), forward_.data(), back_.data(), values_.data(),
                       pivots_.data(), z_.data());
    return;
  }
  if (kernel_ == Kernel::kAvx2) {
    solve_columns_avx2(n, start_.data(), row_.data(), row_start_.data(), row_block_.data(),
                       row_column_.data(), forward_.data(), back_.data(), values_.data(),
                       pivots_.data(), z_.data());
    return;
  }
#endif
  solve_columns(n, start_.data(), row_.data(), row_start_.data(), row_block_.data(),
                row_column_.data(), forward_.data(), back_.data(), values_.data(), pivots_.data(),
                z_.data());
}

}  // namespace dispcon
