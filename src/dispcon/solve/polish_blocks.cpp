// The Newton polish's saddle-point form (groups whose loops share bodies, polish_sparse.cpp)
// factored on blocks (block_ldlt.hpp): each body's six unknowns make a block, and so does each
// run of up to six consecutive rows joining the same two bodies (a joint's rows, usually).
#include <cmath>

#include "dispcon/solve/polish.hpp"

namespace dispcon {

// Blocks 0 ... nv_ - 1 are the bodies, nv_ + k the k-th run of rows. Analysed once per
// pattern, which fixes the runs: a run's rows join the same bodies while the pattern holds.
void Polisher::analyze_blocks() {
  const int m = static_cast<int>(w_->rows_.size());
  big_->run_start_.clear();
  for (int a = 0; a < m; ++a) {
    const Entry& e = w_->rows_[static_cast<size_t>(a)];
    const bool new_run = a == 0 || a - big_->run_start_.back() == BlockLdlt::kSize ||
                         e.v1 != w_->rows_[static_cast<size_t>(a) - 1].v1 ||
                         e.v2 != w_->rows_[static_cast<size_t>(a) - 1].v2;
    if (new_run) big_->run_start_.push_back(a);
  }
  big_->run_start_.push_back(m);
  const int runs = static_cast<int>(big_->run_start_.size()) - 1;
  std::vector<int> sizes(static_cast<size_t>(nv_), BlockLdlt::kSize);
  std::vector<std::pair<int, int>> pairs;
  for (int k = 0; k < runs; ++k) {
    sizes.push_back(big_->run_start_[static_cast<size_t>(k) + 1] -
                    big_->run_start_[static_cast<size_t>(k)]);
    const Entry& e = w_->rows_[static_cast<size_t>(big_->run_start_[static_cast<size_t>(k)])];
    if (e.v1 >= 0) pairs.emplace_back(nv_ + k, e.v1);
    if (e.v2 >= 0) pairs.emplace_back(nv_ + k, e.v2);
  }
  big_->blocks_.analyze(sizes, pairs);
  big_->body_slots_.resize(static_cast<size_t>(nv_));
  for (int v = 0; v < nv_; ++v)
    big_->body_slots_[static_cast<size_t>(v)] = big_->blocks_.slot(v, v);
  big_->run_slots_.resize(static_cast<size_t>(runs));
  for (int k = 0; k < runs; ++k) {
    const Entry& e = w_->rows_[static_cast<size_t>(big_->run_start_[static_cast<size_t>(k)])];
    RunSlots& r = big_->run_slots_[static_cast<size_t>(k)];
    r.diagonal = big_->blocks_.slot(nv_ + k, nv_ + k);
    r.body1 = e.v1 >= 0 ? big_->blocks_.slot(nv_ + k, e.v1) : BlockLdlt::Slot{};
    r.body2 = e.v2 >= 0 ? big_->blocks_.slot(nv_ + k, e.v2) : BlockLdlt::Slot{};
  }
}

//   [ -M   J^T    ]
//   [  J   mu I   ]
bool Polisher::factor_blocks(const SolverState& s, double mu) {
  big_->blocks_.clear();
  for (int v = 0; v < nv_; ++v) {
    const BodyState& b = s.bodies[static_cast<size_t>(group_->bodies[static_cast<size_t>(v)])];
    const Mat3 inertia = b.inverse_inertia().inverse();  // rotation block of M
    const BlockLdlt::Slot d = big_->body_slots_[static_cast<size_t>(v)];
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k) big_->blocks_.at(d, i, k) = -inertia(i, k);
      big_->blocks_.at(d, 3 + i, 3 + i) = -b.m;
    }
  }
  const int runs = static_cast<int>(big_->run_slots_.size());
  for (int k = 0; k < runs; ++k) {
    const RunSlots& r = big_->run_slots_[static_cast<size_t>(k)];
    const int first = big_->run_start_[static_cast<size_t>(k)];
    for (int a = first; a < big_->run_start_[static_cast<size_t>(k) + 1]; ++a) {
      const Entry& e = w_->rows_[static_cast<size_t>(a)];
      const int o = a - first;
      big_->blocks_.at(r.diagonal, o, o) = mu + soft(a);
      if (e.v1 >= 0) {
        for (int i = 0; i < 6; ++i) big_->blocks_.at(r.body1, o, i) += e.j1(i);
      }
      if (e.v2 >= 0) {
        for (int i = 0; i < 6; ++i) big_->blocks_.at(r.body2, o, i) += e.j2(i);
      }
    }
  }
  return big_->blocks_.factorize();
}

// The right-hand side [0; -r], and dq from the solution, in place in the factorisation's own
// vector (a copy into the caller's numbering and back cost a tenth of the solve).
bool Polisher::solve_blocks(const std::vector<double>& residual) {
  big_->blocks_.clear_values();
  const int runs = static_cast<int>(big_->run_slots_.size());
  for (int k = 0; k < runs; ++k) {
    const int first = big_->run_start_[static_cast<size_t>(k)];
    double* x = big_->blocks_.values_of(nv_ + k);
    for (int a = first; a < big_->run_start_[static_cast<size_t>(k) + 1]; ++a) {
      x[a - first] = -residual[static_cast<size_t>(a)];
    }
  }
  big_->blocks_.solve();
  bool finite = true;
  for (int v = 0; v < nv_; ++v) {
    Vec6& d = w_->dq_[static_cast<size_t>(v)];
    d = Eigen::Map<const Vec6>(big_->blocks_.values_of(v));
    finite = finite && d.allFinite();
  }
  return finite;
}

// The rows' impulses y of the last solve_blocks(), one a row in row order, into the work's y_:
// the solution's run blocks. With [-M J^T; J mu I] [dq; z] = [0; -r], dq = M^-1 J^T z and
// (J M^-1 J^T + mu) z = -r: z is the rows form's y. False when one is not finite.
bool Polisher::blocks_multipliers() {
  const int m = static_cast<int>(w_->rows_.size());
  w_->y_.resize(static_cast<size_t>(m));
  bool finite = true;
  const int runs = static_cast<int>(big_->run_slots_.size());
  for (int k = 0; k < runs; ++k) {
    const int first = big_->run_start_[static_cast<size_t>(k)];
    const double* z = big_->blocks_.values_of(nv_ + k);
    for (int a = first; a < big_->run_start_[static_cast<size_t>(k) + 1]; ++a) {
      const double y = z[a - first];
      w_->y_[static_cast<size_t>(a)] = y;
      finite = finite && std::isfinite(y);
    }
  }
  return finite;
}

}  // namespace dispcon
