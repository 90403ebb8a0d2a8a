// SparseLdlt against Eigen's SimplicialLDLT (the same arithmetic in the same order: the same bits)
// and against a dense solve, on random positive definite systems whose pattern fills in, and
// refactored with new values on the same pattern.
#include "dispcon/solve/sparse_ldlt.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <random>

namespace dispcon {
namespace {

// A random symmetric positive definite n x n matrix with about `per_column` entries a column
// below the diagonal (a sum of sparse outer products plus a diagonal), dense.
Eigen::MatrixXd random_system(int n, int per_column, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_int_distribution<int> pick(0, n - 1);
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int k = 0; k < n * per_column / 2; ++k) {
    const int i = pick(rng), j = pick(rng);
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    v(i) = u(rng);
    v(j) += u(rng);
    a += v * v.transpose();
  }
  for (int i = 0; i < n; ++i) a(i, i) += 0.1 + std::abs(u(rng));
  return a;
}

// Lays out the upper triangle of `a` in `f` (pattern, then values) and analyses it.
void write_upper(const Eigen::MatrixXd& a, SparseLdlt& f, bool analyze) {
  const int n = static_cast<int>(a.rows());
  if (analyze) {
    f.starts.assign(1, 0);
    f.rows.clear();
    for (int c = 0; c < n; ++c) {
      for (int r = 0; r <= c; ++r) {
        if (a(r, c) != 0) f.rows.push_back(r);
      }
      f.starts.push_back(static_cast<int>(f.rows.size()));
    }
    f.values.resize(f.rows.size());
    f.analyze();
  }
  for (int c = 0; c < n; ++c) {
    for (int p = f.starts[static_cast<size_t>(c)]; p < f.starts[static_cast<size_t>(c) + 1]; ++p) {
      f.values[static_cast<size_t>(p)] = a(f.rows[static_cast<size_t>(p)], c);
    }
  }
}

TEST(SparseLdlt, GivesEigensBitsAndTheDenseSolution) {
  std::mt19937 rng(3);
  for (int n : {1, 7, 60, 300}) {
    const Eigen::MatrixXd a = random_system(n, 3, rng);
    SparseLdlt f;
    write_upper(a, f, true);
    ASSERT_TRUE(f.factorize()) << n;
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1, 2);
    std::copy(b.data(), b.data() + n, f.rhs());
    f.solve();
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(f.rhs(), n);

    const Eigen::SparseMatrix<double> sparse = a.sparseView();
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>>
        eigen(sparse);
    ASSERT_EQ(eigen.info(), Eigen::Success);
    const Eigen::VectorXd expected = eigen.solve(b);
    for (int i = 0; i < n; ++i) EXPECT_EQ(x(i), expected(i)) << "n " << n << ", unknown " << i;
    EXPECT_LT((a * x - b).norm(), 1e-10 * b.norm()) << n;
  }
}

TEST(SparseLdlt, RefactorsWithNewValuesOnTheSamePattern) {
  std::mt19937 rng(5);
  const Eigen::MatrixXd a = random_system(80, 4, rng);
  SparseLdlt f;
  write_upper(a, f, true);
  for (double shift : {0.0, 1.0, 1e3}) {
    Eigen::MatrixXd shifted = a;
    shifted.diagonal().array() += shift;
    write_upper(shifted, f, false);
    ASSERT_TRUE(f.factorize());
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(80);
    std::copy(b.data(), b.data() + 80, f.rhs());
    f.solve();
    const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(f.rhs(), 80);
    EXPECT_LT((shifted * x - b).norm(), 1e-10 * b.norm()) << "shift " << shift;
  }
}

TEST(SparseLdlt, RefusesAZeroPivot) {
  // [[1, 1], [1, 1]]: the second pivot is 1 - 1 = 0.
  SparseLdlt f;
  f.starts = {0, 1, 3};
  f.rows = {0, 0, 1};
  f.values = {1, 1, 1};
  f.analyze();
  EXPECT_FALSE(f.factorize());
}

}  // namespace
}  // namespace dispcon
