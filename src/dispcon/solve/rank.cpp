#include "dispcon/solve/rank.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "dispcon/solve/group.hpp"
#include "dispcon/solve/jacobian.hpp"
#include "dispcon/solve/state.hpp"

namespace dispcon {

namespace {

constexpr double kRankTolerance = 1e-8;

// The SVD of a block: Eigen's divide and conquer, which takes one-sided Jacobi below 16 columns
// (every small group's, bit for bit as before) and bidiagonalises larger ones: a 100-part chain's
// 735 x 594 block took 5 s in Jacobi's sweeps alone. Its error is a few eps of the largest
// singular value, far under the rank's tolerance (1e-8 of it) and the one-pass test's margins.
using Svd = Eigen::BDCSVD<Eigen::MatrixXd>;

// A's singular values, largest first (none when A is empty).
template <typename M>
Eigen::VectorXd singular_values(const M& A) {
  if (A.rows() == 0 || A.cols() == 0) return {};
  return Svd(A).singularValues();
}

int rank_from(const Eigen::VectorXd& s) {
  if (s.size() == 0 || s(0) == 0) return 0;
  int r = 0;
  for (Eigen::Index k = 0; k < s.size(); ++k) r += s(k) > kRankTolerance * s(0);
  return r;
}

template <typename M>
int rank_of(const M& A) {
  return rank_from(singular_values(A));
}

// Every row scaled to unit norm (a row in radians and a row in lengths weigh the same), then
// every column. A body's columns are non-zero only in the rows of joints that touch it, all in
// its group, so a group's block is scaled exactly as it would be within the whole matrix.
void equilibrate(Eigen::MatrixXd& A) {
  if (A.rows() == 0 || A.cols() == 0) return;  // no body can move: an empty row has no data
  for (Eigen::Index r = 0; r < A.rows(); ++r) {
    const double n = A.row(r).norm();
    if (n > 0) A.row(r) /= n;
  }
  // Rotation and translation columns have different units; scaling a column changes neither the
  // rank nor which body a null-space direction moves.
  for (Eigen::Index c = 0; c < A.cols(); ++c) {
    const double n = A.col(c).norm();
    if (n > 0) A.col(c) /= n;
  }
}

// A diagonal block of the Jacobian: the columns of some movable bodies, the rows of some joints.
struct Block {
  std::vector<int> bodies;
  std::vector<int> joints;  // in model order
};

// The Jacobian's rows are laid out joint after joint: where each joint's begin, and how many.
struct Rows {
  explicit Rows(const ConstraintJacobian& cj, int joint_count)
      : start(static_cast<size_t>(joint_count) + 1, 0) {
    for (const JacobianRow& r : cj.rows) ++start[static_cast<size_t>(r.joint.value) + 1];
    for (size_t c = 1; c < start.size(); ++c) start[c] += start[c - 1];
  }
  int begin(int c) const { return start[static_cast<size_t>(c)]; }
  int count(int c) const { return start[static_cast<size_t>(c) + 1] - begin(c); }
  std::vector<int> start;
};

// The redundant joints of a block in one pass, without the SVD of every leading block of rows
// (one per joint: a hundred-part chain's Check took minutes). The rows of each joint in turn have
// what the rows before them span taken out (twice, for the rounding); the singular values of what
// is left say how many of them add rank, and their directions join the basis. It gives the SVDs'
// answers where they are not close: a value left far above the rank's tolerance (over 1e-5 of the
// block's largest singular value, `scale`) is new rank, one far under it (under 1e-10 of the
// largest row so far, the left-overs of every repeated row together under 1e-9 of it: the
// leading block's new singular value is at most that) repeats, and the new ranks add up to the
// block's (`rank`). Otherwise it returns false having added nothing, and the caller takes the
// SVDs.
bool repeated_in_one_pass(const Eigen::MatrixXd& A, const Block& b, const Rows& rows, int rank,
                          double scale, std::vector<Repeated>& redundant) {
  if (A.rows() == 0 || A.cols() == 0 || rank <= 0 || !(scale > 0)) return false;
  Eigen::MatrixXd basis(A.cols(), rank);  // orthonormal columns: the rows' span so far
  Eigen::Index spanned = 0, row = 0;
  double largest_row = 0, left_over = 0;  // the latter squared
  std::vector<Repeated> found;
  for (int c : b.joints) {
    const int k = rows.count(c);
    if (k == 0) continue;
    largest_row = std::max(largest_row, A.middleRows(row, k).rowwise().norm().maxCoeff());
    Eigen::MatrixXd left = A.middleRows(row, k).transpose();
    row += k;
    for (int pass = 0; pass < 2 && spanned > 0; ++pass) {
      left -= basis.leftCols(spanned) * (basis.leftCols(spanned).transpose() * left);
    }
    Svd svd(left, Eigen::ComputeThinU);
    const auto& s = svd.singularValues();
    int added = 0;
    for (Eigen::Index i = 0; i < s.size(); ++i) {
      if (s(i) > 1e-5 * scale) {
        ++added;
      } else if (s(i) < 1e-10 * largest_row) {
        left_over += s(i) * s(i);
      } else {
        return false;  // close: the SVDs decide
      }
    }
    if (spanned + added > rank || !(std::sqrt(left_over) < 1e-9 * largest_row)) return false;
    basis.middleCols(spanned, added) = svd.matrixU().leftCols(added);
    spanned += added;
    if (added < k) found.push_back(Repeated{JointId{c}, k, k - added});
  }
  if (spanned != rank) return false;
  redundant.insert(redundant.end(), found.begin(), found.end());
  return true;
}

// Ranks one block and adds its answers to `out`. `column` maps a Jacobian column to the block's
// (-1 elsewhere); it is left as it was found.
void analyse(const Block& b, const ConstraintJacobian& cj, const Rows& rows,
             std::vector<int>& column, RankReport& out) {
  const int n = 6 * static_cast<int>(b.bodies.size());
  int m = 0;
  for (int c : b.joints) m += rows.count(c);
  for (size_t k = 0; k < b.bodies.size(); ++k) {
    for (int d = 0; d < 6; ++d)
      column[static_cast<size_t>(6 * b.bodies[k] + d)] = 6 * static_cast<int>(k) + d;
  }
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m, n);
  int r = 0;
  for (int c : b.joints) {
    for (int i = rows.begin(c); i < rows.begin(c) + rows.count(c); ++i, ++r) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(cj.J, i); it; ++it) {
        const int col = column[static_cast<size_t>(it.col())];
        if (col >= 0) A(r, col) = it.value();
      }
    }
  }
  for (int body : b.bodies) {
    for (int d = 0; d < 6; ++d) column[static_cast<size_t>(6 * body + d)] = -1;
  }
  equilibrate(A);
  // One SVD gives the rank and the nullspace (its singular values are those of an SVD without
  // V: V only gathers the rotations).
  Svd svd;
  if (m > 0 && n > 0) svd.compute(A, Eigen::ComputeFullV);
  const Eigen::VectorXd singular = m > 0 && n > 0 ? svd.singularValues() : Eigen::VectorXd();
  const int dof = n - rank_from(singular);
  out.dof += dof;

  // Per body: how many independent motions it has in the block's nullspace.
  if (m == 0) {
    for (int body : b.bodies) out.body_dof[static_cast<size_t>(body)] = 6;
  } else if (dof > 0) {
    const Eigen::MatrixXd N = svd.matrixV().rightCols(dof);
    // N's columns are orthonormal, so its singular values are at most 1: a body's rows count
    // against that scale, not against their own largest value (a body that does not move has
    // rows of rounding noise, which a relative test would count as a motion).
    for (size_t k = 0; k < b.bodies.size(); ++k) {
      Eigen::JacobiSVD<Eigen::MatrixXd> rows_svd(N.middleRows(6 * static_cast<Eigen::Index>(k), 6));
      const auto& s = rows_svd.singularValues();
      int motions = 0;
      for (Eigen::Index i = 0; i < s.size(); ++i) motions += s(i) > kRankTolerance;
      out.body_dof[static_cast<size_t>(b.bodies[k])] = motions;
    }
  }

  // Redundant: going through the joints in order, a joint whose rows add less rank than they
  // count repeats equations of the joints before it.
  if (repeated_in_one_pass(A, b, rows, n - dof, singular.size() ? singular(0) : 0.0, out.redundant))
    return;
  int acc_rows = 0, acc_rank = 0;
  for (int c : b.joints) {
    const int k = rows.count(c);
    if (k == 0) continue;
    const int next_rank = rank_of(A.topRows(acc_rows + k));
    const int repeated = k - (next_rank - acc_rank);
    if (repeated > 0) out.redundant.push_back(Repeated{JointId{c}, k, repeated});
    acc_rows += k;
    acc_rank = next_rank;
  }
}

RankReport analyse_blocks(const Model& model, const SolveOptions& options,
                          const std::vector<Block>& blocks) {
  const ConstraintJacobian cj = constraint_jacobian(model, model.poses(), options);
  const Rows rows(cj, model.joint_count());
  std::vector<int> column(static_cast<size_t>(cj.J.cols()), -1);
  RankReport out;
  out.body_dof.assign(static_cast<size_t>(model.body_count()), 0);
  for (const Block& b : blocks) analyse(b, cj, rows, column, out);
  std::sort(out.redundant.begin(), out.redundant.end(),
            [](const Repeated& a, const Repeated& b) { return a.joint.value < b.joint.value; });
  return out;
}

}  // namespace

RankReport rank_by_group(const Model& model, const SolveOptions& options) {
  const SolverState s(model, model.poses(), options, {});
  std::vector<Block> blocks;
  for (Group& g : find_groups(s)) blocks.push_back(Block{std::move(g.bodies), std::move(g.joints)});
  // Joints between two bodies that cannot move have rows without columns: all repeated.
  Block immovable;
  for (size_t c = 0; c < s.joints.size(); ++c) {
    const JointState& js = s.joints[c];
    if (js.active && !s.bodies[static_cast<size_t>(js.b1)].movable &&
        !s.bodies[static_cast<size_t>(js.b2)].movable) {
      immovable.joints.push_back(static_cast<int>(c));
    }
  }
  blocks.push_back(std::move(immovable));
  return analyse_blocks(model, options, blocks);
}

RankReport rank_whole(const Model& model, const SolveOptions& options) {
  Block all;
  for (int i = 1; i < model.body_count(); ++i) {
    if (!model.body(BodyId{i}).fixed) all.bodies.push_back(i);
  }
  for (int c = 0; c < model.joint_count(); ++c) all.joints.push_back(c);
  return analyse_blocks(model, options, {all});
}

}  // namespace dispcon
