#include "dispcon/solve/solver.hpp"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <deque>
#include <exception>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "dispcon/solve/state.hpp"

namespace dispcon {

namespace {

// The poses handed to a solve: one per body, each finite and within range (the door for poses
// that do not come from the model). Cheap when they are: nothing is allocated.
void check_poses(const Model& model, const std::vector<Pose>& poses) {
  if (static_cast<int>(poses.size()) != model.body_count()) {
    throw std::invalid_argument("solve: one pose per body expected");
  }
  for (size_t i = 0; i < poses.size(); ++i) {
    const Pose& p = poses[i];
    if (!p.x.allFinite() || !(p.x.cwiseAbs().maxCoeff() <= kLargest) ||
        !p.q.coeffs().allFinite() || !(p.q.coeffs().cwiseAbs().maxCoeff() > 0)) {
      check_pose(p, "position", "solve: object '" + model.body(BodyId{static_cast<int>(i)}).name + "'");
    }
  }
}

Vec3 clamp_norm(const Vec3& v, double limit) {
  const double n = v.norm();
  return n > limit ? Vec3(v * (limit / n)) : v;
}

// Bodies that move together: joined by active joints through movable bodies. Components are
// independent problems; each iterates until it holds, so a converged part of a large assembly
// costs nothing while the rest works.
struct Component {
  std::vector<int> bodies;  // movable bodies
  std::vector<int> joints;  // active joints touching them
};

std::vector<Component> components(const SolverState& s) {
  const int n = static_cast<int>(s.bodies.size());
  std::vector<int> parent(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) parent[static_cast<size_t>(i)] = i;
  auto find = [&](int i) {
    while (parent[static_cast<size_t>(i)] != i) {
      parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
      i = parent[static_cast<size_t>(i)];
    }
    return i;
  };
  for (const JointState& js : s.joints) {
    if (js.active && s.bodies[static_cast<size_t>(js.b1)].movable &&
        s.bodies[static_cast<size_t>(js.b2)].movable) {
      parent[static_cast<size_t>(find(js.b1))] = find(js.b2);
    }
  }
  std::vector<int> index(static_cast<size_t>(n), -1);
  std::vector<Component> out;
  for (int i = 0; i < n; ++i) {
    if (!s.bodies[static_cast<size_t>(i)].movable) continue;
    int& k = index[static_cast<size_t>(find(i))];
    if (k < 0) k = static_cast<int>(out.size()), out.emplace_back();
    out[static_cast<size_t>(k)].bodies.push_back(i);
  }
  for (size_t c = 0; c < s.joints.size(); ++c) {
    const JointState& js = s.joints[c];
    if (!js.active) continue;
    const int b = s.bodies[static_cast<size_t>(js.b1)].movable ? js.b1 : js.b2;
    if (!s.bodies[static_cast<size_t>(b)].movable) continue;
    out[static_cast<size_t>(index[static_cast<size_t>(find(b))])].joints.push_back(
        static_cast<int>(c));
  }
  return out;
}

// The largest violation of some joints; each joint's own goes to `store` (indexed by joint), so
// the final report need not measure again.
// A non-finite residual makes the result infinite (std::max would drop a NaN).
double max_residual(const SolverState& s, const std::vector<int>& joints,
                    std::vector<double>& store) {
  double r = 0;
  for (int c : joints) {
    const double rc = s.residual(s.joints[static_cast<size_t>(c)]);
    store[static_cast<size_t>(c)] = rc;
    if (!(rc <= r)) r = std::isnan(rc) ? std::numeric_limits<double>::infinity() : rc;
  }
  return r;
}

// One iteration of seed 3.2: propose, weight by 1/max(n_i, n_j), combine rotations, apply;
// then the same for translations (from the rotated positions, eq. 19, or from the same positions
// as the rotations, eq. 15).
void jacobi_iteration(SolverState& s, const Component& comp, const SolveOptions& o) {
  for (int b : comp.bodies) {
    s.bodies[static_cast<size_t>(b)].dR.setZero();
    s.bodies[static_cast<size_t>(b)].dx.setZero();
  }
  // Only the group's own (movable) bodies are written: groups may run on several threads, and
  // the bodies that cannot move (the world, fixed parts) are shared between them.
  Vec3 d1, d2;
  auto add = [&](int b, Vec3 BodyState::*field, const Vec3& d, double w) {
    BodyState& body = s.bodies[static_cast<size_t>(b)];
    if (body.movable) body.*field += w * d;
  };
  auto add_translations = [&](const JointState& js) {
    s.propose_translations(js, d1, d2);
    add(js.b1, &BodyState::dx, d1, js.w);
    add(js.b2, &BodyState::dx, d2, js.w);
  };
  for (int c : comp.joints) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    s.propose_rotations(js, d1, d2);
    add(js.b1, &BodyState::dR, d1, js.w);
    add(js.b2, &BodyState::dR, d2, js.w);
    if (!o.translate_after_rotate) add_translations(js);
  }
  for (int b : comp.bodies) {
    BodyState& body = s.bodies[static_cast<size_t>(b)];
    body.displace(clamp_norm(body.dR, o.max_rotation_step), Vec3::Zero());
  }
  if (o.translate_after_rotate) {
    for (int c : comp.joints) add_translations(s.joints[static_cast<size_t>(c)]);
  }
  for (int b : comp.bodies) {
    BodyState& body = s.bodies[static_cast<size_t>(b)];
    body.displace(Vec3::Zero(), body.dx);
  }
}

// Gauss-Seidel ordering: each joint's correction is applied at once, in model order.
void gauss_seidel_iteration(SolverState& s, const Component& comp, const SolveOptions& o) {
  Vec3 d1, d2;
  const double w = o.relaxation;
  for (int c : comp.joints) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    BodyState& b1 = s.bodies[static_cast<size_t>(js.b1)];
    BodyState& b2 = s.bodies[static_cast<size_t>(js.b2)];
    s.propose_rotations(js, d1, d2);
    if (b1.movable) b1.displace(clamp_norm(w * d1, o.max_rotation_step), Vec3::Zero());
    if (b2.movable) b2.displace(clamp_norm(w * d2, o.max_rotation_step), Vec3::Zero());
    s.propose_translations(js, d1, d2);
    if (b1.movable) b1.displace(Vec3::Zero(), w * d1);
    if (b2.movable) b2.displace(Vec3::Zero(), w * d2);
  }
}

// Solves A y = b in place for a small symmetric positive definite A given by its lower triangle
// (column-major, overwritten by the factor L). Column-oriented so every inner loop runs over
// contiguous memory; for the few dozen rows of a mechanism's component this beats the general
// blocked factorisations. Returns false when a pivot is not positive.
bool cholesky_solve(Eigen::Ref<Eigen::MatrixXd> A, Eigen::Ref<Eigen::VectorXd> y) {
  const Eigen::Index m = A.rows();
  double* a = A.data();
  for (Eigen::Index j = 0; j < m; ++j) {
    double* cj = a + j * m;
    for (Eigen::Index k = 0; k < j; ++k) {
      const double* ck = a + k * m;
      const double f = ck[j];
      if (f == 0) continue;
      for (Eigen::Index i = j; i < m; ++i) cj[i] -= f * ck[i];
    }
    if (!(cj[j] > 0)) return false;
    const double d = std::sqrt(cj[j]);
    cj[j] = d;
    const double inv = 1 / d;
    for (Eigen::Index i = j + 1; i < m; ++i) cj[i] *= inv;
  }
  double* x = y.data();
  for (Eigen::Index j = 0; j < m; ++j) {  // L z = b
    const double* cj = a + j * m;
    x[j] /= cj[j];
    const double xj = x[j];
    for (Eigen::Index i = j + 1; i < m; ++i) x[i] -= xj * cj[i];
  }
  for (Eigen::Index j = m - 1; j >= 0; --j) {  // L^T y = z
    const double* cj = a + j * m;
    double sum = x[j];
    for (Eigen::Index i = j + 1; i < m; ++i) sum -= cj[i] * x[i];
    x[j] = sum / cj[j];
  }
  return true;
}

// Scratch space of the Newton polish, shared by the components of a session (they are solved one
// after another): warm after the first, so the iterations allocate nothing.
struct PolishWork {
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  struct Entry {
    int v1 = -1, v2 = -1;  // unknowns of the two bodies, -1 when the body does not move
    Vec6 j1, j2;           // the row's two 6-blocks
    Vec6 u1, u2;           // M^-1 times them
  };
  std::vector<Entry> rows_;
  std::vector<double> residual_;
  std::vector<int> var_start_, fill_;          // rows of body v: var_rows_[var_start_[v] ...]
  std::vector<std::pair<int, int>> var_rows_;  // (row, side 1 or 2)
  std::vector<Vec6> dq_;
  // Plain buffers under Eigen maps: groups of different sizes share them, and an Eigen matrix
  // would reallocate at every change of size.
  std::vector<double> y_;
  std::vector<double> dense_;
  Eigen::MatrixXd full_;  // the fallback LDLT's copy
  Eigen::LDLT<Eigen::MatrixXd> dense_ldlt_;
  std::vector<Eigen::Triplet<double>> triplets_;
  std::vector<int> pattern_;
  std::vector<double> rows_per_body_;
};

// Newton polish. The step is dq = M^-1 J^T y with (J M^-1 J^T + lambda I) y = -r: the
// displacement produced by constraint impulses J^T y, opposite on the two bodies of each joint,
// so it conserves first-order momenta like the seed's corrections; lambda regularises redundant
// rows (a planar linkage in 3D) and damps far from the solution (Levenberg-Marquardt).
// J M^-1 J^T is assembled body by body (rows sharing a body couple); small systems are factored
// dense, large ones sparse, reusing the sparse symbolic analysis while the rows keep their pattern.
class Polisher {
 public:
  explicit Polisher(const Component& comp)
      : comp_(&comp), nv_(static_cast<int>(comp.bodies.size())) {}

  // `band[c]` widens what counts as a bound in contact for joint c (see solve()).
  // Returns false when no step could be computed.
  // With `reuse`, a large group in the saddle-point form may solve with the factorisation of its
  // last step instead of a new one (a chord step: the Jacobian moved little since); reused()
  // tells whether it did.
  bool step(SolverState& s, PolishWork& work, const std::vector<double>& band, double lambda,
            double max_rotation, bool reuse) {
    w_ = &work;
    reused_ = false;
    w_->dq_.resize(static_cast<size_t>(nv_));
    for (int v = 0; v < nv_; ++v)
      s.bodies[static_cast<size_t>(comp_->bodies[static_cast<size_t>(v)])].n_var = v;
    gather(s, band);
    const int m = static_cast<int>(w_->rows_.size());
    if (m == 0 || nv_ == 0) return false;
    if (reuse && factored_ && m > kDenseRows && kkt_ && same_pattern()) {
      reused_ = true;
      if (!solve_factored()) return false;
    } else if (!factor(s, lambda)) {
      return false;
    }
    if (m <= kDenseRows || !kkt_) {
      // dq = M^-1 J^T y
      for (Vec6& d : w_->dq_) d.setZero();
      for (int a = 0; a < m; ++a) {
        const Entry& e = w_->rows_[static_cast<size_t>(a)];
        const double ya = w_->y_[static_cast<size_t>(a)];
        if (e.v1 >= 0) w_->dq_[static_cast<size_t>(e.v1)] += ya * e.u1;
        if (e.v2 >= 0) w_->dq_[static_cast<size_t>(e.v2)] += ya * e.u2;
      }
    }
    // Keep each body's turn small (seed 2.3): scale the whole step, never bend it.
    double largest = 0;
    for (const Vec6& d : w_->dq_) {
      if (!d.allFinite()) return false;
      largest = std::max(largest, d.head<3>().norm());
    }
    const double scale = largest > max_rotation ? max_rotation / largest : 1.0;
    for (int v = 0; v < nv_; ++v) {
      const Vec6& d = w_->dq_[static_cast<size_t>(v)];
      s.bodies[static_cast<size_t>(comp_->bodies[static_cast<size_t>(v)])].displace(
          scale * d.head<3>(), scale * d.tail<3>());
    }
    return true;
  }
  bool reused() const { return reused_; }

 private:
  using Vec6 = PolishWork::Vec6;
  using Entry = PolishWork::Entry;

  void gather(const SolverState& s, const std::vector<double>& band) {
    w_->rows_.clear();
    w_->residual_.clear();
    PartRows parts[3];
    for (int c : comp_->joints) {
      const JointState& js = s.joints[static_cast<size_t>(c)];
      const BodyState& s1 = s.bodies[static_cast<size_t>(js.b1)];
      const BodyState& s2 = s.bodies[static_cast<size_t>(js.b2)];
      const int v1 = s1.movable ? s1.n_var : -1;
      const int v2 = s2.movable ? s2.n_var : -1;
      s.rows(js, BoundTest{band[static_cast<size_t>(c)]}, parts);
      for (const PartRows& p : parts) {
        for (int k = 0; k < p.count; ++k) {
          Entry e;
          e.v1 = v1;
          e.v2 = v2;
          e.j1 = p.J[k].segment<6>(0).transpose();
          e.j2 = p.J[k].segment<6>(6).transpose();
          e.u1 = apply_inverse_mass(s.bodies[static_cast<size_t>(js.b1)], e.j1);
          e.u2 = apply_inverse_mass(s.bodies[static_cast<size_t>(js.b2)], e.j2);
          w_->rows_.push_back(e);
          w_->residual_.push_back(p.residual[k]);
        }
      }
    }
  }

  static Vec6 apply_inverse_mass(const BodyState& b, const Vec6& j) {
    Vec6 u;
    u.head<3>() = b.K * (b.inv_m * j.head<3>());
    u.tail<3>() = b.inv_m * j.tail<3>();
    return u;
  }

  // Calls f(a, b, value) for every coupling a >= b of J M^-1 J^T, body by body. The rows of
  // each body are listed flat (counted, then placed), so nothing is allocated once warm.
  template <typename F>
  void couplings(F&& f) {
    w_->var_start_.assign(static_cast<size_t>(nv_) + 1, 0);
    for (const Entry& e : w_->rows_) {
      if (e.v1 >= 0) ++w_->var_start_[static_cast<size_t>(e.v1) + 1];
      if (e.v2 >= 0) ++w_->var_start_[static_cast<size_t>(e.v2) + 1];
    }
    for (int v = 0; v < nv_; ++v)
      w_->var_start_[static_cast<size_t>(v) + 1] += w_->var_start_[static_cast<size_t>(v)];
    w_->var_rows_.resize(static_cast<size_t>(w_->var_start_.back()));
    w_->fill_.assign(w_->var_start_.begin(), w_->var_start_.end() - 1);
    for (int a = 0; a < static_cast<int>(w_->rows_.size()); ++a) {
      const Entry& e = w_->rows_[static_cast<size_t>(a)];
      if (e.v1 >= 0)
        w_->var_rows_[static_cast<size_t>(w_->fill_[static_cast<size_t>(e.v1)]++)] = {a, 1};
      if (e.v2 >= 0)
        w_->var_rows_[static_cast<size_t>(w_->fill_[static_cast<size_t>(e.v2)]++)] = {a, 2};
    }
    for (int v = 0; v < nv_; ++v) {
      const int begin = w_->var_start_[static_cast<size_t>(v)];
      const int end = w_->var_start_[static_cast<size_t>(v) + 1];
      for (int p = begin; p < end; ++p) {
        const auto [ra, sa] = w_->var_rows_[static_cast<size_t>(p)];
        const Entry& ea = w_->rows_[static_cast<size_t>(ra)];
        const Vec6& ja = sa == 1 ? ea.j1 : ea.j2;
        for (int q = begin; q <= p; ++q) {
          const auto [rb, sb] = w_->var_rows_[static_cast<size_t>(q)];
          const Entry& eb = w_->rows_[static_cast<size_t>(rb)];
          f(ra, rb, ja.dot(sb == 1 ? eb.u1 : eb.u2));
        }
      }
    }
  }

  // Large groups: the same step from the sparse saddle-point system
  //   [ -M   J^T    ] [dq]   [ 0]
  //   [  J   mu I   ] [ y] = [-r],   mu = lambda * max diag(J M^-1 J^T),
  // whose first block row is dq = M^-1 J^T y and whose second is (J M^-1 J^T + mu I) y = -r.
  // J M^-1 J^T couples every pair of rows that share a body (a body with many joints makes a
  // dense clique); this system only links each row to its two bodies, so its factor stays
  // sparse where loops share bodies. It is quasi-definite, so the LDLT needs no pivoting and
  // the fill-reducing order is found once per pattern.
  template <typename F>
  void kkt_entries(const SolverState& s, double mu, F&& f) const {
    const int base = 6 * nv_;
    for (int v = 0; v < nv_; ++v) {
      const BodyState& b = s.bodies[static_cast<size_t>(comp_->bodies[static_cast<size_t>(v)])];
      const Mat3 inertia = b.inverse_inertia().inverse();  // rotation block of M
      for (int i = 0; i < 3; ++i) {
        for (int k = 0; k <= i; ++k) f(6 * v + i, 6 * v + k, -inertia(i, k));
        f(6 * v + 3 + i, 6 * v + 3 + i, -b.m);
      }
    }
    for (int a = 0; a < static_cast<int>(w_->rows_.size()); ++a) {
      const Entry& e = w_->rows_[static_cast<size_t>(a)];
      if (e.v1 >= 0) {
        for (int i = 0; i < 6; ++i) f(base + a, 6 * e.v1 + i, e.j1(i));
      }
      if (e.v2 >= 0) {
        for (int i = 0; i < 6; ++i) f(base + a, 6 * e.v2 + i, e.j2(i));
      }
      f(base + a, base + a, mu);
    }
  }

  bool factor(const SolverState& s, double lambda) {
    const int m = static_cast<int>(w_->rows_.size());
    const Eigen::Map<const Eigen::VectorXd> r(w_->residual_.data(), m);
    if (m <= kDenseRows) {
      // Lower triangle only; Cholesky first (the regularised matrix is positive definite), the
      // pivoting LDLT only when rounding defeats it.
      w_->dense_.resize(static_cast<size_t>(m) * static_cast<size_t>(m));
      w_->y_.resize(static_cast<size_t>(m));
      Eigen::Map<Eigen::MatrixXd> A(w_->dense_.data(), m, m);
      Eigen::Map<Eigen::VectorXd> y(w_->y_.data(), m);
      auto assemble = [&] {
        A.triangularView<Eigen::Lower>().setZero();
        couplings([&](int a, int b, double v) { A(a, b) += v; });
        const double scale = A.diagonal().maxCoeff();
        A.diagonal().array() += lambda * scale;
        return scale;
      };
      if (!(assemble() > 0)) return false;
      y = -r;
      if (cholesky_solve(A, y)) return y.allFinite();
      assemble();
      w_->full_ = A.selfadjointView<Eigen::Lower>();
      w_->dense_ldlt_.compute(w_->full_);
      if (w_->dense_ldlt_.info() != Eigen::Success) return false;
      y = w_->dense_ldlt_.solve(-r);
      return y.allFinite();
    }
    return factor_sparse(s, lambda);
  }

  // Large groups are solved sparse, in one of two forms with the same solution: J M^-1 J^T
  // itself (chains: a few rows per body), or the saddle-point system above when bodies carry
  // many rows (loops sharing bodies), whose every row only touches its two bodies. The form with
  // fewer entries is taken; that was also the faster one on the benchmarks' chains and grids.
  // While the pattern holds, the fill-reducing order (AMD) and the symbolic analysis are kept,
  // and the values are written in place, pre-ordered in the upper triangle (slots_ remembers
  // where each entry lands), so the factorisation reads the matrix without a copy.
  bool factor_sparse(const SolverState& s, double lambda) {
    const int m = static_cast<int>(w_->rows_.size());
    double scale = 0;  // the largest diagonal entry of J M^-1 J^T
    for (const Entry& e : w_->rows_) {
      scale = std::max(scale, (e.v1 >= 0 ? e.j1.dot(e.u1) : 0) + (e.v2 >= 0 ? e.j2.dot(e.u2) : 0));
    }
    if (!(scale > 0)) return false;
    const double mu = lambda * scale;
    auto rows_form = [&](auto&& f) {
      couplings(f);
      for (int a = 0; a < m; ++a) f(a, a, mu);
    };
    auto kkt_form = [&](auto&& f) { kkt_entries(s, mu, f); };
    factored_ = false;
    if (!same_pattern()) {
      std::vector<double>& per_body = w_->rows_per_body_;
      per_body.assign(static_cast<size_t>(nv_), 0.0);
      for (const Entry& e : w_->rows_) {
        if (e.v1 >= 0) per_body[static_cast<size_t>(e.v1)] += 1;
        if (e.v2 >= 0) per_body[static_cast<size_t>(e.v2)] += 1;
      }
      double rows_entries = 0;  // lower triangle, counting rows that share two bodies twice
      for (double k : per_body) rows_entries += k * (k + 1) / 2;
      const double kkt_entries = 9.0 * nv_ + 13.0 * m;
      kkt_ = kkt_entries < rows_entries;
      if (kkt_) {
        analyze(6 * nv_ + m, kkt_form);
      } else {
        analyze(m, rows_form);
      }
      analyzed_pattern_ = w_->pattern_;
      analyzed_ = true;
    }
    double* values = sparse_.valuePtr();
    std::fill(values, values + sparse_.nonZeros(), 0.0);
    size_t visit = 0;
    auto write = [&](int, int, double v) { values[slots_[visit++]] += v; };
    if (kkt_) {
      kkt_form(write);
    } else {
      rows_form(write);
    }
    sparse_ldlt_.factorize(sparse_);
    if (sparse_ldlt_.info() != Eigen::Success) return false;
    factored_ = kkt_;
    return solve_factored();
  }

  // Whether the rows join the same bodies as when the sparse system was analysed.
  bool same_pattern() {
    w_->pattern_.clear();
    for (const Entry& e : w_->rows_) w_->pattern_.push_back(e.v1), w_->pattern_.push_back(e.v2);
    return analyzed_ && w_->pattern_ == analyzed_pattern_;
  }

  // The step from the current residuals with the factorisation in hand.
  bool solve_factored() {
    const int m = static_cast<int>(w_->rows_.size());
    const int base = kkt_ ? 6 * nv_ : 0;
    rhs_.setZero(base + m);
    for (int a = 0; a < m; ++a) rhs_(order_(base + a)) = -w_->residual_[static_cast<size_t>(a)];
    solution_ = sparse_ldlt_.solve(rhs_);
    if (kkt_) {
      for (int v = 0; v < nv_; ++v) {
        Vec6& d = w_->dq_[static_cast<size_t>(v)];
        for (int i = 0; i < 6; ++i) d(i) = solution_(order_(6 * v + i));
      }
    } else {
      w_->y_.resize(static_cast<size_t>(m));
      for (int a = 0; a < m; ++a) w_->y_[static_cast<size_t>(a)] = solution_(order_(a));
    }
    return solution_.allFinite();
  }

  // Orders, places and analyses an n x n system given by its lower-triangle entries (in a fixed
  // order).
  template <typename Form>
  void analyze(int n, Form&& form) {
    w_->triplets_.clear();
    form([&](int a, int b, double v) { w_->triplets_.emplace_back(a, b, v); });
    Eigen::SparseMatrix<double> lower(n, n);
    lower.setFromTriplets(w_->triplets_.begin(), w_->triplets_.end());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> inverse;
    Eigen::AMDOrdering<int>()(lower.selfadjointView<Eigen::Lower>(), inverse);
    // Row a goes to order_[a] (Eigen's orderings return the inverse permutation).
    const Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> forward = inverse.inverse();
    order_ = forward.indices();
    for (auto& t : w_->triplets_) t = reordered(t.row(), t.col(), t.value());
    sparse_.resize(n, n);
    sparse_.setFromTriplets(w_->triplets_.begin(), w_->triplets_.end());
    sparse_.makeCompressed();
    slots_.clear();
    form([&](int a, int b, double) { slots_.push_back(slot(reordered(a, b))); });
    sparse_ldlt_.analyzePattern(sparse_);
  }

  // Entry (a, b) in the reordered matrix's upper triangle.
  Eigen::Triplet<double> reordered(int a, int b, double v = 0) const {
    const int pa = order_(a), pb = order_(b);
    return Eigen::Triplet<double>(std::min(pa, pb), std::max(pa, pb), v);
  }

  // Index in sparse_'s values of an upper-triangle entry (column-major).
  int slot(const Eigen::Triplet<double>& t) const {
    const int* inner = sparse_.innerIndexPtr();
    const int* begin = inner + sparse_.outerIndexPtr()[t.col()];
    const int* end = inner + sparse_.outerIndexPtr()[t.col() + 1];
    return static_cast<int>(std::lower_bound(begin, end, t.row()) - inner);
  }

  static constexpr int kDenseRows = 120;
  const Component* comp_;
  int nv_ = 0;
  PolishWork* w_ = nullptr;  // the session's scratch space, during step()
  Eigen::SparseMatrix<double> sparse_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>>
      sparse_ldlt_;
  bool kkt_ = false;       // the sparse system is the saddle-point form
  bool factored_ = false;  // ... and its factorisation can serve a chord step
  bool reused_ = false;    // the last step was a chord step
  Eigen::VectorXi order_;  // fill-reducing order of the rows
  Eigen::VectorXd rhs_, solution_;
  std::vector<int> analyzed_pattern_;
  std::vector<int> slots_;
  bool analyzed_ = false;
};

std::string describe(const Model& model, const ConstraintReport& c) {
  const Joint& j = model.joint(c.joint);
  std::ostringstream out;
  out << "joint " << c.joint.value;
  if (c.line) out << " (line " << c.line << ")";
  out << " " << model.body(j.body1).name << " / " << model.body(j.body2).name << " residual "
      << c.residual;
  return out.str();
}

// `known`, when given, holds every joint's residual at the current poses.
std::vector<ConstraintReport> report(const SolverState& s, double tolerance,
                                     const std::vector<double>* known = nullptr) {
  std::vector<ConstraintReport> out;
  out.reserve(s.joints.size());
  for (size_t c = 0; c < s.joints.size(); ++c) {
    const JointState& js = s.joints[c];
    ConstraintReport r;
    r.joint = JointId{static_cast<int>(c)};
    r.line = js.joint->line;
    r.active = js.active;
    r.residual = known ? (*known)[c] : s.residual(js);
    r.satisfied = r.residual <= tolerance;
    r.at_limit = js.active && js.bounded && s.at_limit(js, contact_band(tolerance));
    out.push_back(r);
  }
  return out;
}

}  // namespace

const char* to_string(SolveStatus status) {
  switch (status) {
    case SolveStatus::Converged:
      return "converged";
    case SolveStatus::IterationLimit:
      return "iteration-limit";
    case SolveStatus::Stalled:
      return "stalled";
    case SolveStatus::Diverged:
      return "diverged";
  }
  return "?";
}

void validate(const SolveOptions& o) {
  auto positive = [](double v, const char* name) {
    check_number(v, name, name);
    if (!(v > 0)) throw ValueError(name, std::string(name) + " " + format_number(v) + " must be positive");
  };
  positive(o.tolerance, "tolerance");
  if (o.max_iterations < 1) {
    throw ValueError("max_iterations",
                     "max_iterations " + std::to_string(o.max_iterations) + " must be at least 1");
  }
  check_number(o.time, "time", "time");
  positive(o.relaxation, "relaxation");
  positive(o.max_rotation_step, "max_rotation_step");
  check_number(o.polish_below, "polish_below", "polish_below");
  if (o.polish_below < 0) throw ValueError("polish_below", "polish_below must not be negative");
  if (o.threads < 0) throw ValueError("threads", "threads must not be negative");
}

std::vector<JointId> SolveResult::violated() const {
  std::vector<JointId> out;
  for (const ConstraintReport& c : constraints) {
    if (!c.satisfied) out.push_back(c.joint);
  }
  return out;
}

std::vector<ConstraintReport> measure(const Model& model, const std::vector<Pose>& poses,
                                      const SolveOptions& options) {
  validate(options);
  check_poses(model, poses);
  const SolverState s(model, poses, options, {});
  return report(s, options.tolerance);
}

namespace {

// Iterations without a 0.1 % gain in the best violation after which a group is given up.
constexpr int kStallIterations = 400;

// One component's progress through the loop.
struct Progress {
  explicit Progress(const Component& c) : comp(&c), polisher(c) {}
  const Component* comp;
  Polisher polisher;
  double r = 0;       // largest violation now
  double best_r = 0;  // and the best seen, whose poses are kept
  double size = 1;    // the group's size when the session was made: where the polish begins
  double lambda = 1e-12;
  bool chord = false;  // the next Newton step may reuse the last factorisation (kept across solves)
  int iterations = 0, seed = 0, polish = 0;
  int seed_only_until = 0;   // after a failed polish, let the seed iterations work a while
  int last_progress = 0;     // the iteration at which the best violation last shrank by 0.1 %
  double progress_mark = 0;  // the best violation then
  bool stalled = false;
  bool done = false;
  std::vector<double> history;  // r after each iteration (record_history)

  // Ready for another solve; the polisher keeps its symbolic analysis.
  void reset() {
    lambda = 1e-12;
    iterations = seed = polish = seed_only_until = last_progress = 0;
    stalled = false;
    done = false;
    history.clear();
  }
};

// A group's size: the diagonal of the box around its bodies and its joints' points. The switch to
// Newton steps is relative to it, so a group solves the same whatever else is in the model.
double size(const SolverState& s, const Component& comp) {
  Eigen::AlignedBox3d box;
  for (int b : comp.bodies) {
    box.extend(s.bodies[static_cast<size_t>(b)].x);
    box.extend(s.bodies[static_cast<size_t>(b)].G);
  }
  for (int c : comp.joints) {
    const JointState& js = s.joints[static_cast<size_t>(c)];
    const BodyState& b1 = s.bodies[static_cast<size_t>(js.b1)];
    const BodyState& b2 = s.bodies[static_cast<size_t>(js.b2)];
    box.extend(b1.R * js.joint->p1 + b1.x);
    box.extend(b2.R * js.joint->p2 + b2.x);
    if (js.joint->guide) {
      for (const Vec3& q : js.joint->guide->points) box.extend(b1.R * q + b1.x);
    }
  }
  return box.isEmpty() ? 1e-6 : std::max(1e-6, box.diagonal().norm());
}

void save_poses(const SolverState& s, const Component& comp, std::vector<Pose>& out) {
  for (int b : comp.bodies) out[static_cast<size_t>(b)] = s.bodies[static_cast<size_t>(b)].pose();
}

void load_poses(SolverState& s, const Component& comp, const std::vector<Pose>& in) {
  for (int b : comp.bodies) s.bodies[static_cast<size_t>(b)].set_pose(in[static_cast<size_t>(b)]);
}

// One iteration of one component: a Newton polish step once close, else a seed iteration.
// Limits enter the Newton step only when violated. A step that pushes a limit that was not in
// the step over its bound is redone with that limit held at its bound: its band (what counts as
// contact) is widened to cover the distance the step moved it, so the active set grows instead
// of the step being damped.
void iterate(SolverState& s, Progress& p, PolishWork& work, const SolveOptions& o,
             std::vector<double>& band, std::vector<Pose>& before, std::vector<double>& joint_r) {
  const Component& comp = *p.comp;
  const double polish_threshold = o.polish_below * p.size;
  ++p.iterations;
  const bool polish = o.newton_polish && p.r < polish_threshold && p.iterations > p.seed_only_until;
  if (!polish) {
    if (o.scheme == Scheme::Jacobi) {
      jacobi_iteration(s, comp, o);
    } else {
      gauss_seidel_iteration(s, comp, o);
    }
    ++p.seed;
    p.r = max_residual(s, comp.joints, joint_r);
    return;
  }
  ++p.polish;
  save_poses(s, comp, before);
  const bool stepped = p.polisher.step(s, work, band, p.lambda, o.max_rotation_step, p.chord);
  const bool chord = p.polisher.reused();
  const double next = stepped ? max_residual(s, comp.joints, joint_r) : p.r;
  if (stepped && next < p.r) {
    // After a Newton step the next may reuse its factorisation; a chord step that gained less
    // than a hundredfold asks for a new one.
    p.chord = !chord || next < 0.01 * p.r;
    p.r = next;
    p.lambda = std::max(1e-12, p.lambda * 0.1);
    return;
  }
  if (chord) {  // the old factorisation no longer serves: try again with a new one
    load_poses(s, comp, before);
    p.chord = false;
    return;
  }
  bool widened = false;
  if (stepped) {
    for (int c : comp.joints) {
      const JointState& js = s.joints[static_cast<size_t>(c)];
      double& b = band[static_cast<size_t>(c)];
      const double rc = s.residual(js);
      if (rc > p.r && b < polish_threshold && s.at_limit(js, -0.5 * o.tolerance)) {
        b = std::max(4 * b, 2 * rc + o.tolerance);
        widened = true;
      }
    }
  }
  load_poses(s, comp, before);
  if (!widened) p.lambda *= 100;
  if (!stepped || p.lambda > 1e-2) {
    p.lambda = 1e-12;
    p.seed_only_until = p.iterations + 10;
  }
}

}  // namespace

// Threads for a solve: SolveOptions::threads when given; by default every core, but only when
// there are several groups and about a millisecond of work between them (a thousand joints):
// starting threads costs tens of microseconds, which a drag step of a hundred parts cannot pay
// (a closed chain held at one link splits in two groups: two threads made its step 4 times
// slower).
int thread_count(const SolveOptions& o, const std::vector<Component>& comps) {
  if (o.threads == 1 || comps.size() < 2) return 1;
  size_t joints = 0;
  for (const Component& c : comps) joints += c.joints.size();
  if (o.threads <= 0 && joints < 1000) return 1;
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  const int wanted = o.threads > 1 ? o.threads : std::max(1, cores);
  return std::min(wanted, static_cast<int>(comps.size()));
}

struct Session::Impl {
  Impl(const Model& m, const SolveOptions& opt, const std::vector<bool>& held_bodies)
      : model((validate(opt), m)),
        revision(m.revision()),
        held(held_bodies),
        o(opt),
        s(m, m.poses(), opt, held_bodies),
        comps(components(s)) {
    for (const Component& c : comps) progress.emplace_back(c);
    band.assign(s.joints.size(), -0.5 * opt.tolerance);
    for (Progress& p : progress) p.size = size(s, *p.comp);
    threads = thread_count(opt, comps);
    more_work.resize(static_cast<size_t>(std::max(0, threads - 1)));
    for (size_t c = 0; c < s.joints.size(); ++c) {
      const JointState& js = s.joints[c];
      if (js.active && !s.bodies[static_cast<size_t>(js.b1)].movable &&
          !s.bodies[static_cast<size_t>(js.b2)].movable) {
        immovable.push_back(static_cast<int>(c));
      }
    }
  }
  const Model& model;
  std::uint64_t revision;  // the model's when this was built
  std::vector<bool> held;
  SolveOptions o;
  SolverState s;
  std::vector<Component> comps;
  std::deque<Progress> progress;  // not moved once built: each holds its factorisation
  std::vector<double> band;
  std::vector<Pose> best, before;
  std::vector<double> joint_r;  // each joint's residual at the current poses
  PolishWork work;
  std::deque<PolishWork> more_work;  // one per extra thread
  int threads = 1;                   // threads a solve uses
  std::vector<int> immovable;        // active joints whose two bodies cannot move
};

Session::Session(const Model& model, const SolveOptions& options, const std::vector<bool>& held)
    : impl_(std::make_unique<Impl>(model, options, held)) {}
Session::~Session() = default;
Session::Session(Session&&) noexcept = default;
Session& Session::operator=(Session&&) noexcept = default;

SolveResult solve(const Model& model, std::vector<Pose>& poses, const SolveOptions& o,
                  const std::vector<bool>& held) {
  return Session(model, o, held).solve(poses);
}

namespace {

// The one line for people: what happened and the joints at fault (the worst five).
std::string solve_message(const Model& model, const SolveResult& result) {
  std::ostringstream msg;
  if (result.converged) {
    msg << "converged in " << result.iterations << " iterations (max residual "
        << result.max_residual << ")";
    return msg.str();
  }
  if (result.status == SolveStatus::Diverged) {
    msg << "diverged after " << result.iterations
        << " iterations (a residual or a pose became infinite or not a number; the poses were "
           "not changed); at fault: ";
  } else {
    msg << "did not converge after " << result.iterations << " iterations"
        << (result.status == SolveStatus::Stalled
                ? " (no progress: over-constrained or unreachable)"
                : "")
        << "; still violated: ";
  }
  std::vector<ConstraintReport> bad;
  for (const ConstraintReport& c : result.constraints) {
    if (!c.satisfied) bad.push_back(c);
  }
  // Non-finite first (a NaN compares false, so it is ranked as infinite).
  auto key = [](double r) { return std::isnan(r) ? std::numeric_limits<double>::infinity() : r; };
  std::stable_sort(bad.begin(), bad.end(),
                   [&](const ConstraintReport& a, const ConstraintReport& b) {
                     return key(a.residual) > key(b.residual);
                   });
  for (size_t k = 0; k < bad.size() && k < 5; ++k) {
    msg << (k ? "; " : "") << describe(model, bad[k]);
  }
  if (bad.empty()) msg << "no joint (a body's pose)";
  if (bad.size() > 5) msg << "; and " << bad.size() - 5 << " more";
  return msg.str();
}

bool all_finite(const std::vector<Pose>& poses) {
  for (const Pose& p : poses) {
    if (!p.x.allFinite() || !p.q.coeffs().allFinite()) return false;
  }
  return true;
}

}  // namespace

SolveResult Session::solve(std::vector<Pose>& poses) {
  if (impl_->model.revision() != impl_->revision) {
    // The model changed since this session was built: its joints may have moved in memory.
    std::vector<bool> held = impl_->held;
    if (!held.empty()) held.resize(static_cast<size_t>(impl_->model.body_count()), false);
    impl_ = std::make_unique<Impl>(impl_->model, impl_->o, held);
  }
  const Model& model = impl_->model;
  const SolveOptions& o = impl_->o;
  check_poses(model, poses);
  SolverState& s = impl_->s;
  s.read_poses(poses);
  std::vector<double>& joint_r = impl_->joint_r;
  joint_r.assign(s.joints.size(), 0.0);
  SolveResult result;
  std::deque<Progress>& progress = impl_->progress;
  std::atomic<bool> finite{true};
  for (Progress& p : progress) {
    p.reset();
    p.r = p.best_r = p.progress_mark = max_residual(s, p.comp->joints, joint_r);
    p.done = p.r <= o.tolerance;
    if (!std::isfinite(p.r)) finite = false;
  }
  std::vector<Pose>& best = impl_->best;
  std::vector<Pose>& before = impl_->before;
  best = poses;
  before = poses;
  std::vector<double>& band = impl_->band;
  std::fill(band.begin(), band.end(), -0.5 * o.tolerance);
  // Each group runs to the end before the next starts, so its working set stays in cache; with
  // many groups, several threads take the next unsolved group in turn (each group touches only
  // its own bodies and joints, so the answer does not depend on the threads).
  auto run = [&](Progress& p, PolishWork& work) {
    for (int k = 0; !p.done && k < o.max_iterations; ++k) {
      iterate(s, p, work, o, band, before, joint_r);
      if (!std::isfinite(p.r)) {
        finite = false;
        return;
      }
      if (p.r < p.best_r) {
        p.best_r = p.r;
        save_poses(s, *p.comp, best);
      }
      // An over-constrained or unreachable problem stops improving: give up early rather than
      // run to the cap (a drag step that cannot be made should fail fast).
      if (p.best_r < (1 - 1e-3) * p.progress_mark) {
        p.progress_mark = p.best_r;
        p.last_progress = p.iterations;
      } else if (p.iterations - p.last_progress > kStallIterations) {
        p.stalled = true;
      }
      p.done = p.r <= o.tolerance || p.stalled;
      if (o.record_history) p.history.push_back(p.r);
    }
  };
  const int threads = impl_->threads;
  if (threads <= 1) {
    for (Progress& p : progress) {
      if (!finite) break;
      run(p, impl_->work);
    }
  } else {
    std::atomic<size_t> next{0};
    std::vector<std::exception_ptr> errors(static_cast<size_t>(threads));
    auto worker = [&](int t) {
      try {
        PolishWork& work = t == 0 ? impl_->work : impl_->more_work[static_cast<size_t>(t - 1)];
        for (size_t i; finite && (i = next++) < progress.size();) run(progress[i], work);
      } catch (...) {
        errors[static_cast<size_t>(t)] = std::current_exception();
        finite = false;
      }
    };
    std::vector<std::thread> pool;
    for (int t = 1; t < threads; ++t) pool.emplace_back(worker, t);
    worker(0);
    for (std::thread& t : pool) t.join();
    for (const std::exception_ptr& e : errors) {
      if (e) std::rethrow_exception(e);
    }
  }
  for (const Progress& p : progress) result.iterations = std::max(result.iterations, p.iterations);
  if (o.record_history) {
    // The largest violation over groups after each iteration, as if they had advanced in
    // lockstep (a group that finished early keeps its last violation).
    result.history.assign(static_cast<size_t>(result.iterations), 0.0);
    for (const Progress& p : progress) {
      for (size_t k = 0; k < result.history.size(); ++k) {
        result.history[k] = std::max(result.history[k], k < p.history.size() ? p.history[k] : p.r);
      }
    }
  }
  // The poses reached: a group that did not have to move keeps the bits it was given.
  result.poses = poses;
  double r = 0;
  bool any_stalled = false;
  for (Progress& p : progress) {
    if ((!p.done || p.stalled) && finite) {
      load_poses(s, *p.comp, best);  // not converged: keep the best poses seen
      p.r = p.best_r;
      max_residual(s, p.comp->joints, joint_r);
    }
    if (p.iterations > 0) save_poses(s, *p.comp, result.poses);
    any_stalled = any_stalled || p.stalled;
    r = std::max(r, p.r);
    if (p.iterations == result.iterations) {
      result.seed_iterations = std::max(result.seed_iterations, p.seed);
      result.polish_iterations = std::max(result.polish_iterations, p.polish);
    }
  }
  // Joints between bodies that cannot move are measured too: nothing can fix them.
  r = std::max(r, max_residual(s, impl_->immovable, joint_r));
  if (!std::isfinite(r) || !all_finite(result.poses)) finite = false;
  if (!finite) {
    // Named by their residuals where it happened; the poses go back to those given, bit for bit.
    result.status = SolveStatus::Diverged;
    result.converged = false;
    result.max_residual = std::numeric_limits<double>::infinity();
    result.constraints = report(s, o.tolerance, &joint_r);
    result.poses = poses;
    s.read_poses(poses);
  } else {
    if (r > o.tolerance) {
      result.status = any_stalled ? SolveStatus::Stalled : SolveStatus::IterationLimit;
      result.converged = false;
    }
    result.max_residual = r;
    result.constraints = report(s, o.tolerance, &joint_r);
  }
  if (result.converged) poses = result.poses;
  result.message = solve_message(model, result);
  return result;
}

SolveResult assemble(Model& model, const SolveOptions& options) {
  std::vector<Pose> poses = model.poses();
  SolveResult r = solve(model, poses, options);
  if (r.converged) model.set_poses(poses);
  return r;
}

namespace {

std::vector<bool> held_only(const Model& model, BodyId body) {
  if (body.value <= 0 || body.value >= model.body_count()) {
    throw std::invalid_argument("drag: unknown body");
  }
  if (model.body(body).fixed) {
    throw std::invalid_argument("drag: object '" + model.body(body).name + "' is fixed");
  }
  std::vector<bool> held(static_cast<size_t>(model.body_count()), false);
  held[static_cast<size_t>(body.value)] = true;
  return held;
}

}  // namespace

Dragger::Dragger(Model& model, BodyId body, const SolveOptions& options)
    : model_(model), body_(body), session_(model, options, held_only(model, body)) {}

SolveResult Dragger::move_to(const Pose& target) {
  poses_ = model_.poses();
  poses_[static_cast<size_t>(body_.value)] =
      check_pose(target, "target", "drag: target of '" + model_.body(body_).name + "'");
  SolveResult r = session_.solve(poses_);
  if (r.converged) model_.set_poses(poses_);
  return r;
}

DragResult drag(Model& model, BodyId body, const Pose& target, int steps,
                const SolveOptions& options, std::vector<std::vector<Pose>>* step_poses) {
  if (steps < 1) throw ValueError("steps", "drag: steps must be at least 1");
  Dragger dragger(model, body, options);
  const Pose goal = check_pose(target, "target", "drag: target of '" + model.body(body).name + "'");
  const std::vector<Pose> given = model.poses();
  DragResult out;
  const SolveResult first = assemble(model, options);
  out.iterations = first.iterations;
  out.max_residual = first.max_residual;
  if (!first.converged) {
    out.converged = false;
    out.failed_step = 0;
    out.message = "the model does not assemble: " + first.message;
    return out;
  }
  const Pose start = model.body(body).pose;
  for (int k = 1; k <= steps; ++k) {
    const double t = static_cast<double>(k) / steps;
    Pose p;
    p.x = (1 - t) * start.x + t * goal.x;
    p.q = start.q.slerp(t, goal.q).normalized();
    SolveResult r = dragger.move_to(p);
    out.iterations += r.iterations;
    out.max_residual = std::max(out.max_residual, r.max_residual);
    const bool ok = r.converged;
    out.steps.push_back(std::move(r));
    if (!ok) {
      out.converged = false;
      out.failed_step = k - 1;
      // No step was made: the assembly alone is not a drag, so nothing changes.
      if (k == 1) model.set_poses(given);
      break;
    }
    if (step_poses) step_poses->push_back(model.poses());
  }
  std::ostringstream msg;
  if (out.converged) {
    msg << "dragged '" << model.body(body).name << "' in " << steps << " steps, " << out.iterations
        << " iterations";
  } else {
    msg << "step " << out.failed_step + 1 << " of " << steps << " failed, '"
        << model.body(body).name << "' left "
        << (out.failed_step == 0 ? std::string("where it was")
                                 : "at step " + std::to_string(out.failed_step))
        << ": " << out.steps.back().message;
  }
  out.message = msg.str();
  return out;
}

}  // namespace dispcon
