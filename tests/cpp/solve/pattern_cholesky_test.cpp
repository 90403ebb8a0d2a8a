// The pattern Cholesky against the dense column algorithm it replaced: the same factor and the
// same solution, bit for bit, on systems shaped like the polish's (rows that share no body or no
// component make exact zeros), and the same refusals.
#include "dispcon/solve/pattern_cholesky.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

namespace dispcon {
namespace {

// The dense column Cholesky the polish used before (left-looking, each column updated by the
// columns before it in order, a zero multiplier skipped), then the two triangular solves.
bool dense_cholesky_solve(std::vector<double>& a, int m, std::vector<double>& x) {
  for (int j = 0; j < m; ++j) {
    double* cj = a.data() + j * m;
    for (int k = 0; k < j; ++k) {
      const double* ck = a.data() + k * m;
      const double f = ck[j];
      if (f == 0) continue;
      for (int i = j; i < m; ++i) cj[i] -= f * ck[i];
    }
    if (!(cj[j] > 0)) return false;
    const double d = std::sqrt(cj[j]);
    cj[j] = d;
    const double inv = 1 / d;
    for (int i = j + 1; i < m; ++i) cj[i] *= inv;
  }
  for (int j = 0; j < m; ++j) {
    const double* cj = a.data() + j * m;
    x[j] /= cj[j];
    for (int i = j + 1; i < m; ++i) x[i] -= x[j] * cj[i];
  }
  for (int j = m - 1; j >= 0; --j) {
    const double* cj = a.data() + j * m;
    double sum = x[j];
    for (int i = j + 1; i < m; ++i) sum -= cj[i] * x[i];
    x[j] = sum / cj[j];
  }
  return true;
}

// J M^-1 J^T + mu I as the polish assembles it (each place summed from +0), for m rows each
// joining two of `bodies` bodies with six components, each component non-zero with probability
// `density`; rows of one joint (runs of up to five) join the same two bodies.
std::vector<double> polish_like(int m, int bodies, double density, double mu, std::mt19937& rng) {
  std::uniform_real_distribution<double> value(-1, 1), unit(0, 1);
  std::uniform_int_distribution<int> body(0, bodies - 1);
  const int n = 6 * bodies;
  std::vector<double> J(static_cast<size_t>(m * n), 0.0);
  int b1 = 0, b2 = 0;
  for (int a = 0; a < m; ++a) {
    if (a % 5 == 0) b1 = body(rng), b2 = body(rng);
    for (int side : {b1, b2}) {
      for (int c = 0; c < 6; ++c) {
        if (unit(rng) < density) J[static_cast<size_t>(a * n + 6 * side + c)] = value(rng);
      }
    }
  }
  std::vector<double> A(static_cast<size_t>(m * m), 0.0);
  for (int j = 0; j < m; ++j) {
    for (int i = j; i < m; ++i) {
      double& v = A[static_cast<size_t>(j * m + i)];
      for (int c = 0; c < n; ++c) {
        v += J[static_cast<size_t>(i * n + c)] * J[static_cast<size_t>(j * n + c)];
      }
    }
    A[static_cast<size_t>(j * m + j)] += mu;
  }
  return A;
}

// With `kept` (one kept across systems: its pattern serves the next system whose places are
// the same, and only that one), else a fresh PatternCholesky.
void expect_same_as_dense(std::vector<double> A, int m, std::mt19937& rng,
                          PatternCholesky* kept = nullptr) {
  std::uniform_real_distribution<double> value(-1, 1);
  std::vector<double> b(static_cast<size_t>(m));
  for (double& v : b) v = value(rng);
  b[0] = 0;  // a row that holds already
  std::vector<double> dense = A, y = b, x = b;
  PatternCholesky fresh;
  PatternCholesky& chol = kept ? *kept : fresh;
  const bool ok = chol.factor(A.data(), m);
  if (ok) chol.solve(A.data(), y.data());
  ASSERT_EQ(ok, dense_cholesky_solve(dense, m, x));
  if (!ok) return;
  for (int j = 0; j < m; ++j) {
    for (int i = j; i < m; ++i) {
      const size_t p = static_cast<size_t>(j * m + i);
      ASSERT_EQ(std::memcmp(&A[p], &dense[p], sizeof(double)), 0)
          << "L(" << i << ", " << j << ") " << A[p] << " against " << dense[p];
    }
  }
  for (int i = 0; i < m; ++i) {
    // The same bits; a zero's sign may differ (a product with +0 that the pattern skips), which
    // the step's dq (summed from +0) cannot see.
    const double yi = y[static_cast<size_t>(i)], xi = x[static_cast<size_t>(i)];
    ASSERT_TRUE(std::memcmp(&yi, &xi, sizeof(double)) == 0 || (yi == 0 && xi == 0))
        << "y(" << i << ") " << yi << " against " << xi;
  }
}

TEST(PatternCholesky, SameBitsAsTheDenseAlgorithm) {
  std::mt19937 rng(14);
  PatternCholesky kept;
  for (int m : {1, 2, 5, 15, 20, 63, 64, 65, 100, 128}) {
    for (double density : {0.1, 0.5, 1.0}) {
      for (int bodies : {1, 2, 3, 8}) {
        // mu = 0 leaves rank-deficient systems (more rows than six a body) to fail alike.
        for (double mu : {1e-12, 0.0, 1.0}) {
          SCOPED_TRACE(::testing::Message() << "m " << m << " density " << density << " bodies "
                                            << bodies << " mu " << mu);
          const std::vector<double> A = polish_like(m, bodies, density, mu, rng);
          expect_same_as_dense(A, m, rng);
          // One factorisation kept across all the systems: each is factored twice, the second
          // time on the pattern found the first.
          expect_same_as_dense(A, m, rng, &kept);
          expect_same_as_dense(A, m, rng, &kept);
        }
      }
    }
  }
}

// A planar linkage posed in 3D: in-plane rows (x, y, the turn about z) and out-of-plane rows
// (z, the two tilts) share no component, so the system splits into two interleaved ones.
TEST(PatternCholesky, InterleavedPlanarSystemAsDense) {
  std::mt19937 rng(1994);
  const int m = 15;
  std::vector<double> A(m * m, 0.0);
  std::uniform_real_distribution<double> value(-1, 1);
  auto in_plane = [](int a) { return a % 5 < 2; };
  for (int j = 0; j < m; ++j) {
    for (int i = j; i < m; ++i) {
      if (in_plane(i) == in_plane(j) && i / 5 - j / 5 <= 1) A[j * m + i] = value(rng);
    }
    A[j * m + j] = 10;
  }
  expect_same_as_dense(A, m, rng);
}

TEST(PatternCholesky, RefusesWhatTheDenseAlgorithmRefuses) {
  std::mt19937 rng(7);
  const int m = 6;
  std::vector<double> A(m * m, 0.0);
  for (int j = 0; j < m; ++j) A[j * m + j] = 1;
  A[2 * m + 2] = -1;  // a negative pivot
  expect_same_as_dense(A, m, rng);
  A[2 * m + 2] = std::numeric_limits<double>::quiet_NaN();  // not a number
  expect_same_as_dense(A, m, rng);
  EXPECT_FALSE(PatternCholesky().factor(A.data(), m));
}

}  // namespace
}  // namespace dispcon
