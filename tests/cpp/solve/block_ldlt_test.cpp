// BlockLdlt against a dense solve of the same system: saddle-point systems [-M J^T; J mu I] of
// random bodies and joints (the shape the Newton polish gives it), with blocks of every size
// from 1 to 6 (the padding), and a pattern that needs fill.
#include "dispcon/solve/block_ldlt.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstring>
#include <random>

namespace dispcon {
namespace {

struct Problem {
  std::vector<int> sizes;                  // bodies' blocks (6), then the joints' runs
  std::vector<std::pair<int, int>> pairs;  // (run, body)
  Eigen::MatrixXd dense;                   // the whole system, unpadded
  std::vector<int> offset;                 // each block's first unknown in `dense`
};

// `bodies` bodies, each joint a run of `sizes` rows joining two of them (or one: the other is
// the ground), with random Jacobian rows and a positive definite M.
Problem saddle(int bodies, const std::vector<std::pair<int, int>>& joints,
               const std::vector<int>& rows, double mu, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Problem p;
  p.sizes.assign(static_cast<size_t>(bodies), 6);
  for (int r : rows) p.sizes.push_back(r);
  int n = 0;
  for (int s : p.sizes) p.offset.push_back(n), n += s;
  p.dense = Eigen::MatrixXd::Zero(n, n);
  for (int v = 0; v < bodies; ++v) {
    const Eigen::MatrixXd a = Eigen::MatrixXd::NullaryExpr(6, 6, [&] { return u(rng); });
    p.dense.block(6 * v, 6 * v, 6, 6) = -(a * a.transpose() + Eigen::MatrixXd::Identity(6, 6));
  }
  for (size_t k = 0; k < joints.size(); ++k) {
    const int block = bodies + static_cast<int>(k);
    const int o = p.offset[static_cast<size_t>(block)], r = rows[k];
    p.dense.block(o, o, r, r) = mu * Eigen::MatrixXd::Identity(r, r);
    for (int v : {joints[k].first, joints[k].second}) {
      if (v < 0) continue;
      p.pairs.emplace_back(block, v);
      const Eigen::MatrixXd j = Eigen::MatrixXd::NullaryExpr(r, 6, [&] { return u(rng); });
      p.dense.block(o, 6 * v, r, 6) += j;
      p.dense.block(6 * v, o, 6, r) += j.transpose();
    }
  }
  return p;
}

// Writes the problem into `f` through its slots, factors, and solves against b; returns the
// largest difference from the dense solution, relative to its size (and the solution itself,
// padded, in `solution`).
double solve_difference(BlockLdlt& f, const Problem& p, const Eigen::VectorXd& b,
                        std::vector<double>* solution = nullptr) {
  f.analyze(p.sizes, p.pairs);
  f.clear();
  const int blocks = static_cast<int>(p.sizes.size());
  auto write = [&](int i, int j) {
    const BlockLdlt::Slot s = f.slot(i, j);
    for (int r = 0; r < p.sizes[static_cast<size_t>(i)]; ++r) {
      for (int c = 0; c < p.sizes[static_cast<size_t>(j)]; ++c) {
        f.at(s, r, c) =
            p.dense(p.offset[static_cast<size_t>(i)] + r, p.offset[static_cast<size_t>(j)] + c);
      }
    }
  };
  for (int i = 0; i < blocks; ++i) write(i, i);
  for (const auto& [i, j] : p.pairs) (i + j) % 2 ? write(i, j) : write(j, i);  // both ways
  EXPECT_TRUE(f.factorize());
  std::vector<double> x(static_cast<size_t>(BlockLdlt::kSize * blocks), 0.0);
  for (int i = 0; i < blocks; ++i) {
    for (int r = 0; r < p.sizes[static_cast<size_t>(i)]; ++r) {
      x[static_cast<size_t>(BlockLdlt::kSize * i + r)] = b(p.offset[static_cast<size_t>(i)] + r);
    }
  }
  f.solve(x.data());
  if (solution) *solution = x;
  const Eigen::VectorXd expected = p.dense.lu().solve(b);
  double worst = 0;
  for (int i = 0; i < blocks; ++i) {
    for (int r = 0; r < BlockLdlt::kSize; ++r) {
      const double got = x[static_cast<size_t>(BlockLdlt::kSize * i + r)];
      if (r >= p.sizes[static_cast<size_t>(i)]) {
        EXPECT_EQ(got, 0.0) << "padding of block " << i;
        continue;
      }
      worst = std::max(worst, std::abs(got - expected(p.offset[static_cast<size_t>(i)] + r)));
    }
  }
  return worst / expected.cwiseAbs().maxCoeff();
}

TEST(BlockLdlt, GridOfLoopsMatchesDenseSolve) {
  std::mt19937 rng(7);
  // A 4 x 4 lattice of bodies, each joined to its right and upper neighbour, the bottom row also
  // to the ground: loops everywhere, so the factor fills in.
  const int side = 4;
  std::vector<std::pair<int, int>> joints;
  std::vector<int> rows;
  for (int r = 0; r < side; ++r) {
    for (int c = 0; c < side; ++c) {
      const int v = r * side + c;
      if (c + 1 < side) joints.emplace_back(v, v + 1);
      if (r + 1 < side) joints.emplace_back(v, v + side);
      if (r == 0) joints.emplace_back(-1, v);
    }
  }
  for (size_t k = 0; k < joints.size(); ++k) rows.push_back(1 + static_cast<int>(k % 6));
  for (double mu : {1.0, 1e-6}) {
    const Problem p = saddle(side * side, joints, rows, mu, rng);
    std::uniform_real_distribution<double> u(-1, 1);
    const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(p.dense.rows(), [&] { return u(rng); });
    BlockLdlt f;
    EXPECT_LT(solve_difference(f, p, b), 1e-9) << "mu " << mu;
    EXPECT_GT(f.stored_blocks(), static_cast<int>(p.sizes.size() + p.pairs.size()))
        << "the lattice's loops fill in";
  }
}

TEST(BlockLdlt, RefactorsWithNewValuesOnTheSamePattern) {
  std::mt19937 rng(11);
  const std::vector<std::pair<int, int>> joints = {{-1, 0}, {0, 1}, {1, 2}, {2, 0}, {0, 1}};
  const std::vector<int> rows = {5, 3, 6, 1, 2};
  BlockLdlt f;
  for (int round = 0; round < 3; ++round) {
    const Problem p = saddle(3, joints, rows, 1e-3, rng);
    const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(p.dense.rows(), -1, 2);
    EXPECT_LT(solve_difference(f, p, b), 1e-10) << "round " << round;
  }
}

// Every kernel the processor has (the baseline always, then AVX2 and AVX-512) against the
// baseline's, the one a processor without AVX2 runs.
TEST(BlockLdlt, KernelsGiveTheSameBits) {
  using Kernel = BlockLdlt::Kernel;
  std::mt19937 rng(13);
  const int side = 5;
  std::vector<std::pair<int, int>> joints;
  std::vector<int> rows;
  for (int v = 0; v < side * side; ++v) {
    if (v % side + 1 < side) joints.emplace_back(v, v + 1);
    if (v + side < side * side) joints.emplace_back(v, v + side);
    if (v < side) joints.emplace_back(-1, v);
  }
  for (size_t k = 0; k < joints.size(); ++k) rows.push_back(k % 3 ? 5 : 3);
  const Problem p = saddle(side * side, joints, rows, 1e-9, rng);
  std::uniform_real_distribution<double> u(-1, 1);
  const Eigen::VectorXd b = Eigen::VectorXd::NullaryExpr(p.dense.rows(), [&] { return u(rng); });
  std::vector<double> base;
  {
    BlockLdlt f;
    ASSERT_TRUE(f.set_kernel(Kernel::kBase));
    ASSERT_EQ(f.kernel(), Kernel::kBase);
    solve_difference(f, p, b, &base);  // (accuracy: the tests above; here, equality)
  }
  int compared = 0;
  for (Kernel k : {Kernel::kAvx2, Kernel::kWide}) {
    BlockLdlt f;
    if (!f.set_kernel(k)) {
      EXPECT_EQ(f.kernel(), BlockLdlt::best_kernel()) << "a refused kernel changed the choice";
      continue;
    }
    ASSERT_EQ(f.kernel(), k);
    std::vector<double> x;
    solve_difference(f, p, b, &x);
    ASSERT_EQ(x.size(), base.size());
    for (size_t i = 0; i < x.size(); ++i) {
      EXPECT_EQ(std::memcmp(&x[i], &base[i], sizeof(double)), 0)
          << "kernel " << static_cast<int>(k) << ", unknown " << i << ": " << x[i]
          << " against the baseline's " << base[i];
    }
    ++compared;
  }
  if (compared == 0) GTEST_SKIP() << "this processor has no AVX2: the baseline alone was checked";
}

TEST(BlockLdlt, RefusesAZeroPivot) {
  // [[1, 1], [1, 1]]: the second pivot is 1 - 1 = 0.
  BlockLdlt f;
  f.analyze({2}, {});
  f.clear();
  const BlockLdlt::Slot d = f.slot(0, 0);
  f.at(d, 0, 0) = f.at(d, 0, 1) = f.at(d, 1, 0) = f.at(d, 1, 1) = 1;
  EXPECT_FALSE(f.factorize());
}

TEST(BlockLdlt, RefusesABlockSizeOutOfRange) {
  BlockLdlt f;
  EXPECT_THROW(f.analyze({6, 7}, {{0, 1}}), std::invalid_argument);
  EXPECT_THROW(f.analyze({0}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace dispcon
