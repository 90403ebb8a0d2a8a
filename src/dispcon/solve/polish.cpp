// The Newton polish's step: gather the rows of the group's joints, factor, apply (scaled so no
// body turns more than the seed allows).
#include "dispcon/solve/polish.hpp"

#include <algorithm>
#include <cstring>

namespace dispcon {

bool Polisher::step(SolverState& s, PolishWork& work, const std::vector<double>& band,
                    double lambda, double max_rotation, bool reuse, bool measured,
                    const std::vector<double>* soft, const LetGo* let_go) {
  w_ = &work;
  s_ = &s;
  reused_ = false;
  const bool first = first_step_;
  first_step_ = false;
  first_chord_done_ = false;
  has_multipliers_ = false;
  kept_ = false;  // the poses move below
  w_->dq_.resize(static_cast<size_t>(nv_));
  for (int v = 0; v < nv_; ++v)
    s.bodies[static_cast<size_t>(group_->bodies[static_cast<size_t>(v)])].n_var = v;
  // A chord step solves with the factorisation in hand: it needs the rows' residuals and the
  // bodies they join (measured with the joints' residuals when the poses have not changed
  // since), not the Jacobian nor M^-1 J^T.
  // A small group's, with its dense factor: still in the work while no other group has gathered
  // since, and only where its rows leave no free motion.
  const bool small = reuse && !soft && small_factored_ && work.caches_.of(Caches::kChord, this) &&
                     small_without_free_motion();
  // The geometry its measure looked at, when these are still the poses it measured.
  const bool kept_geometry = measured && work.caches_.of(Caches::kGeometry, this);
  work.caches_.drop(Caches::kGeometry);  // the poses move below
  if (small) {
    reused_ = small_residuals(s, band, kept_geometry ? work.geometry_.data() : nullptr);
  } else if (reuse && factored_ && kkt_ && !soft) {
    if (!(measured && measured_)) gather_residuals(s, band, nullptr);
    reused_ = 2 * static_cast<size_t>(big_->chord_.rows) == big_->analyzed_pattern_.size() &&
              std::equal(big_->analyzed_pattern_.begin(), big_->analyzed_pattern_.end(),
                         big_->chord_.pattern.begin());
  }
  measured_ = false;  // the poses move below
  if (!reused_) {
    small_factored_ = false;
    work.caches_.drop(Caches::kChord);  // the dense factor and the row lists are rewritten below
    // A large rows-form group's measure of these poses gathered the rows already.
    if (!(measured && !soft && !let_go && work.caches_.of(Caches::kRows, this)))
      gather(s, band, soft, let_go);
  }
  work.caches_.drop(Caches::kRows);  // the poses move below
  const int m = reused_ && !small ? big_->chord_.rows : static_cast<int>(w_->rows_.size());
  if (m == 0 || nv_ == 0) return false;
  if (reused_ && small) {
    Eigen::Map<Eigen::VectorXd> y(w_->y_.data(), m);
    y = -Eigen::Map<const Eigen::VectorXd>(w_->residual_.data(), m);
    w_->chol_.solve(w_->dense_.data(), y.data());
    if (!y.allFinite()) return false;
  } else if (reused_) {
    // A solve's first chord step (a drag's frame) leaves what the Jacobian's drift since the
    // factorisation and the curvature make of its step: much the same from one frame to the
    // next. Extrapolated from the last two frames' and added to the right-hand side, the step
    // meets most of it too (see predict()).
    first_chord_done_ = first;
    const std::vector<double>& rhs = first ? predict() : big_->chord_.residual;
    if (!solve_blocks(rhs)) return false;
  } else if (!factor(s, lambda)) {
    return false;
  }
  if ((!reused_ || small) && (dense() || !kkt_)) {
    has_multipliers_ = !reused_;
    // dq = M^-1 J^T y, each body's terms summed in the order of its rows
    for (Vec6& d : w_->dq_) d.setZero();
    if (dense()) {  // with the M^-1 J^T that row_products() kept
      for (int v = 0; v < nv_; ++v) {
        Vec6& d = w_->dq_[static_cast<size_t>(v)];
        for (int p = w_->var_start_[static_cast<size_t>(v)];
             p < w_->var_start_[static_cast<size_t>(v) + 1]; ++p) {
          const int a = w_->var_rows_[static_cast<size_t>(p)].first;
          d += w_->y_[static_cast<size_t>(a)] * w_->u_[static_cast<size_t>(p)];
        }
      }
    } else {
      for (int a = 0; a < m; ++a) {
        const Entry& e = w_->rows_[static_cast<size_t>(a)];
        const double ya = w_->y_[static_cast<size_t>(a)];
        if (e.v1 >= 0)
          w_->dq_[static_cast<size_t>(e.v1)] += ya * apply_inverse_mass(body(e.v1), e.j1);
        if (e.v2 >= 0)
          w_->dq_[static_cast<size_t>(e.v2)] += ya * apply_inverse_mass(body(e.v2), e.j2);
      }
    }
  }
  // A pull's step in the saddle-point form: its solution holds the impulses y beside dq, which
  // the pull reads to let go of a bound (pull.cpp's Holds).
  if (let_go && !reused_ && !dense() && kkt_) has_multipliers_ = blocks_multipliers();
  // Keep each body's turn small (seed 2.3): scale the whole step, never bend it.
  double largest = 0;
  for (const Vec6& d : w_->dq_) {
    if (!d.allFinite()) return false;
    largest = std::max(largest, d.head<3>().norm());
  }
  cut_short_ = largest > max_rotation;
  const double scale = step_scale_ = cut_short_ ? max_rotation / largest : 1.0;
  for (int v = 0; v < nv_; ++v) {
    const Vec6& d = w_->dq_[static_cast<size_t>(v)];
    s.bodies[static_cast<size_t>(group_->bodies[static_cast<size_t>(v)])].displace(
        scale * d.head<3>(), scale * d.tail<3>());
  }
  return true;
}

namespace {

// Every row of the joints first ... last, in order: `row(c, v1, v2, part, k)` for row k of a
// part of joint c between the variables v1 and v2 (-1 for a body that does not move), then
// `after()` at each joint's end. One walk serves the full gather and the chord step's, which
// keep different things of each row (the chord step's, without `jacobian`, the residuals
// alone). With `joint_r`, each joint's residual is measured in the same look at its geometry
// (as max_residual() does) and the largest returned.
// `let_go`: the bounds a pull has let go, or null.
// `kept`, when given, the geometry of each joint first ... last (kept[i] of first[i]) at the
// current poses (SolverState::residual_keeping()): where it does not depend on the bound test,
// the rows are made from it without looking at the joint again (no `joint_r` then).
template <typename Row, typename After>
double for_each_row(const SolverState& s, const int* first, const int* last,
                    const std::vector<double>& band, const LetGo* let_go, bool jacobian,
                    std::vector<double>* joint_r, Row&& row, After&& after,
                    const JointGeometry* kept = nullptr) {
  PartRows parts[kPartSlots];
  double largest = 0;
  for (const int* joint = first; joint != last; ++joint) {
    const int c = *joint;
    const JointState& js = s.joints[static_cast<size_t>(c)];
    const BodyState& s1 = s.bodies[static_cast<size_t>(js.b1)];
    const BodyState& s2 = s.bodies[static_cast<size_t>(js.b2)];
    const int v1 = s1.movable ? s1.n_var : -1;
    const int v2 = s2.movable ? s2.n_var : -1;
    const BoundTest bound{band[static_cast<size_t>(c)]};
    if (kept && SolverState::geometry_without_bounds(js)) {
      s.rows_from(js, kept[joint - first], bound, parts, jacobian);
    } else if (joint_r) {
      const double rc = s.rows_and_residual(js, bound, parts, jacobian);
      (*joint_r)[static_cast<size_t>(c)] = rc;
      largest = larger_residual(largest, rc);
    } else if (let_go && !let_go->parts.empty()) {
      s.rows(js, JointBounds{bound, let_go->parts[static_cast<size_t>(c)], let_go->band}, parts,
             jacobian);
    } else {
      s.rows(js, bound, parts, jacobian);
    }
    for (const PartRows& p : parts) {
      for (int k = 0; k < p.count; ++k) row(c, v1, v2, p, k);
    }
    after();
  }
  return largest;
}

}  // namespace

double Polisher::gather(const SolverState& s, const std::vector<double>& band,
                        const std::vector<double>* soft, const LetGo* let_go,
                        std::vector<double>* joint_r) {
  w_->caches_.drop(Caches::kRows);
  w_->rows_.clear();
  w_->residual_.clear();
  w_->soft_.clear();
  // Room for as many rows as last time, and at least three a joint (a point's): grown entry by
  // entry, the first gather of a 100,000-link chain copied its 300,000 rows some twenty times
  // (most of a second, in fresh pages).
  const size_t expected = std::max(rows_hint_, 3 * group_->joints.size());
  w_->rows_.reserve(expected);
  w_->residual_.reserve(expected);
  w_->joint_rows_.clear();
  // joint_rows_: where each joint's rows begin (a joint without rows adds no entry), then the end.
  auto mark_boundary = [&] {
    if (w_->joint_rows_.empty() || w_->joint_rows_.back() != static_cast<int>(w_->rows_.size())) {
      w_->joint_rows_.push_back(static_cast<int>(w_->rows_.size()));
    }
  };
  int last = -1;
  const std::vector<int>& joints = group_->joints;
  const double largest = for_each_row(
      s, joints.data(), joints.data() + joints.size(), band, let_go, true, joint_r,
      [&](int c, int v1, int v2, const PartRows& p, int k) {
        if (c != last) {
          mark_boundary();
          last = c;
        }
        Entry e;
        e.v1 = v1;
        e.v2 = v2;
        e.j1 = p.J[k].segment<6>(0).transpose();
        e.j2 = p.J[k].segment<6>(6).transpose();
        w_->rows_.push_back(e);
        w_->residual_.push_back(p.residual[k]);
        if (soft) w_->soft_.push_back((*soft)[static_cast<size_t>(c)]);
      },
      [] {});
  mark_boundary();
  rows_hint_ = w_->rows_.size();
  return largest;
}

// A small group's chord step: the rows' residuals at the current poses into the work's
// residual_, in the order of the rows factored. False when a row joins other unknowns than the
// factored one did, or the rows are others (a bound come into contact or left). `kept`: the
// geometry measure() kept of these poses, or null.
bool Polisher::small_residuals(const SolverState& s, const std::vector<double>& band,
                               const JointGeometry* kept) {
  const std::vector<int>& joints = group_->joints;
  const size_t m = w_->rows_.size();
  size_t a = 0;
  bool same = true;
  for_each_row(
      s, joints.data(), joints.data() + joints.size(), band, nullptr, false, nullptr,
      [&](int, int v1, int v2, const PartRows& p, int k) {
        if (a < m && w_->rows_[a].v1 == v1 && w_->rows_[a].v2 == v2) {
          w_->residual_[a] = p.residual[k];
        } else {
          same = false;
        }
        ++a;
      },
      [] {}, kept);
  return same && a == m;
}

// The rows' residuals alone, and the bodies each row joins (the pattern); with `joint_r`, the
// joints' residuals too (the largest returned).
double Polisher::gather_residuals(const SolverState& s, const std::vector<double>& band,
                                  std::vector<double>* joint_r) {
  const std::vector<int>& joints = group_->joints;
  big_->chord_.start(joints.size());
  int i = 0;
  return for_each_row(
      s, joints.data(), joints.data() + joints.size(), band, nullptr, false, joint_r,
      [&](int, int v1, int v2, const PartRows& p, int k) {
        big_->chord_.add(p.residual[k], v1, v2);
      },
      [&] { big_->chord_.joint[static_cast<size_t>(++i)] = big_->chord_.rows; });
}

double Polisher::measure(const SolverState& s, const std::vector<double>& band,
                         std::vector<double>& joint_r, bool since_kept) {
  // Rows this polisher's last measure gathered are of the poses then: a solve's first measure
  // comes after the poses were given anew (a drag's next frame).
  if (w_) w_->caches_.drop(Caches::kRows | Caches::kGeometry, this);
  // A solve's first measure comes before its first step; the measure after a first chord step
  // keeps what that step left (keep_first_left()).
  first_step_ = since_kept;
  const bool after_first = first_chord_done_ && !since_kept;
  first_chord_done_ = false;
  const bool kept = since_kept && kept_;
  kept_ = false;
  if (since_kept) small_factored_ = false;  // a small group's chord steps stay within a solve
  measured_ = factored_ && kkt_;
  // A large group in the rows form after a step (w_ the step's work): the next step's rows are
  // gathered in the same look at each joint's geometry as its residual (a pass over the
  // 100,000-link chain's joints fewer each step; the last measure's rows go unused).
  if (!since_kept && w_ && analyzed_ && !kkt_ && !dense() && without_couplings(s)) {
    const double largest = gather(s, band, nullptr, nullptr, &joint_r);
    w_->caches_.made(Caches::kRows, this);
    return largest;
  }
  if (!measured_) {
    // A small group whose factorisation may serve a chord step keeps the geometry it looks at,
    // for that step's residuals (a pass over the joints' geometry fewer a chord step: 2,274 of
    // the 400 varied four-bars').
    // (Whether its rows leave free motion is left to the step: worked out here, at every
    // factorisation, it cost more than the geometry saves.)
    if (!since_kept && w_ && small_factored_ && w_->caches_.of(Caches::kChord, this)) {
      return measure_keeping(s, joint_r);
    }
    return max_residual(s, group_->joints, joint_r);
  }
  if (kept) return measure_moved(s, band, joint_r);
  const double largest = gather_residuals(s, band, &joint_r);
  if (after_first) keep_first_left();
  return largest;
}

// The right-hand side of a solve's first chord step: the rows' residuals, plus what the step
// will leave as the last three solves' first steps on this factorisation left it, extrapolated
// by the parabola through them (3 c - 3 b + a: the drift grows frame by frame, the step's size
// changes smoothly along a drag; the line through the last two, 2 c - b, left the grid's first
// steps short of the tolerance in most frames, 2.03 Newton steps a frame against 1.51); from
// two, the line; without two, the residuals alone. What is added is kept in predicted_, to tell
// afterwards what the step would have left without it.
const std::vector<double>& Polisher::predict() {
  Large& g = *big_;
  const auto m = static_cast<size_t>(g.chord_.rows);
  g.predicted_.clear();
  const std::vector<double>& a = g.after_first_[0];
  const std::vector<double>& b = g.after_first_[1];
  const std::vector<double>& c = g.after_first_[2];
  if (g.firsts_ < 2 || b.size() != m || c.size() != m) return g.chord_.residual;
  const bool parabola = g.firsts_ >= 3 && a.size() == m;
  g.predicted_.resize(m);
  g.rhs_.resize(m);
  for (size_t k = 0; k < m; ++k) {
    const double p = parabola ? 3 * c[k] - 3 * b[k] + a[k] : 2 * c[k] - b[k];
    g.predicted_[k] = p;
    g.rhs_[k] = g.chord_.residual[k] + p;
  }
  return g.rhs_;
}

// After a solve's first chord step, measured (chord_): what it left, with what predict() added
// put back (to first order the step met it), as the next solves' predictions read it.
void Polisher::keep_first_left() {
  Large& g = *big_;
  const auto m = static_cast<size_t>(g.chord_.rows);
  if (2 * m != g.analyzed_pattern_.size()) return;  // other rows: nothing to compare
  std::swap(g.after_first_[0], g.after_first_[1]);
  std::swap(g.after_first_[1], g.after_first_[2]);
  std::vector<double>& left = g.after_first_[2];
  left.assign(g.chord_.residual.begin(), g.chord_.residual.begin() + static_cast<long>(m));
  if (g.predicted_.size() == m) {
    for (size_t a = 0; a < m; ++a) left[a] += g.predicted_[a];
  }
  g.firsts_ = std::min(3, g.firsts_ + 1);
}

// max_residual() of the group's joints, each joint's geometry kept in the work (kGeometry).
double Polisher::measure_keeping(const SolverState& s, std::vector<double>& joint_r) {
  const std::vector<int>& joints = group_->joints;
  if (w_->geometry_.size() < joints.size()) w_->geometry_.resize(joints.size());
  double r = 0;
  for (size_t i = 0; i < joints.size(); ++i) {
    const auto c = static_cast<size_t>(joints[i]);
    const double rc = s.residual_keeping(s.joints[c], w_->geometry_[i]);
    joint_r[c] = rc;
    r = larger_residual(r, rc);
  }
  w_->caches_.made(Caches::kGeometry, this);
  return r;
}

namespace {

// A body's rotation and position, bit for bit: all that a joint's rows and residual read of it.
constexpr int kPoseValues = 12;
void copy_pose(const BodyState& b, double* to) {
  std::memcpy(to, b.R.data(), 9 * sizeof(double));
  std::memcpy(to + 9, b.x.data(), 3 * sizeof(double));
}
bool same_pose(const BodyState& b, const double* kept) {
  return std::memcmp(b.R.data(), kept, 9 * sizeof(double)) == 0 &&
         std::memcmp(b.x.data(), kept + 9, 3 * sizeof(double)) == 0;
}
constexpr int kJointValues = 7;  // the residual, p1, p2

}  // namespace

void Polisher::keep_measure(const SolverState& s, const std::vector<double>& joint_r) {
  const std::vector<int>& joints = group_->joints;
  kept_ = measured_ && big_->chord_.joint.size() == joints.size() + 1;
  if (!kept_) return;
  if (big_->joint_touched_.size() != 2 * joints.size()) {  // once: the bodies the joints join
    std::vector<int> slot(s.bodies.size(), -1);
    big_->touched_.clear();
    big_->joint_touched_.clear();
    for (int c : joints) {
      const JointState& js = s.joints[static_cast<size_t>(c)];
      for (int b : {js.b1, js.b2}) {
        int& t = slot[static_cast<size_t>(b)];
        if (t < 0) {
          t = static_cast<int>(big_->touched_.size());
          big_->touched_.push_back(b);
        }
        big_->joint_touched_.push_back(t);
      }
    }
  }
  big_->kept_pose_.resize(kPoseValues * big_->touched_.size());
  for (size_t t = 0; t < big_->touched_.size(); ++t) {
    copy_pose(s.bodies[static_cast<size_t>(big_->touched_[t])],
              big_->kept_pose_.data() + kPoseValues * t);
  }
  big_->kept_joint_.resize(kJointValues * joints.size());
  for (size_t i = 0; i < joints.size(); ++i) {
    const Joint& j = *s.joints[static_cast<size_t>(joints[i])].joint;
    double* k = big_->kept_joint_.data() + kJointValues * i;
    k[0] = joint_r[static_cast<size_t>(joints[i])];
    std::memcpy(k + 1, j.p1.data(), 3 * sizeof(double));
    std::memcpy(k + 4, j.p2.data(), 3 * sizeof(double));
  }
}

// gather_residuals() where a joint's bodies moved, or its rows may depend on more than their
// poses (a bound's band, a coupling's turns, a twist's range); the kept measure elsewhere.
double Polisher::measure_moved(const SolverState& s, const std::vector<double>& band,
                               std::vector<double>& joint_r) {
  const std::vector<int>& joints = group_->joints;
  big_->moved_.resize(big_->touched_.size());
  for (size_t t = 0; t < big_->touched_.size(); ++t) {
    big_->moved_[t] = !same_pose(s.bodies[static_cast<size_t>(big_->touched_[t])],
                                 big_->kept_pose_.data() + kPoseValues * t);
  }
  big_->spare_.start(joints.size());
  double largest = 0;
  for (size_t i = 0; i < joints.size(); ++i) {
    const auto c = static_cast<size_t>(joints[i]);
    const JointState& js = s.joints[c];
    const Joint& j = *js.joint;
    const double* k = big_->kept_joint_.data() + kJointValues * i;
    const bool same = !big_->moved_[static_cast<size_t>(big_->joint_touched_[2 * i])] &&
                      !big_->moved_[static_cast<size_t>(big_->joint_touched_[2 * i + 1])] &&
                      !js.bounded && !j.coupling && !j.twist &&
                      std::memcmp(j.p1.data(), k + 1, 3 * sizeof(double)) == 0 &&
                      std::memcmp(j.p2.data(), k + 4, 3 * sizeof(double)) == 0;
    double rc;
    if (same) {
      rc = k[0];
      const int first = big_->chord_.joint[i], count = big_->chord_.joint[i + 1] - first;
      std::copy_n(big_->chord_.residual.begin() + first, count,
                  big_->spare_.residual.begin() + big_->spare_.rows);
      std::copy_n(big_->chord_.pattern.begin() + 2 * first, 2 * count,
                  big_->spare_.pattern.begin() + 2 * big_->spare_.rows);
      big_->spare_.rows += count;
    } else {
      rc = for_each_row(
          s, &joints[i], &joints[i] + 1, band, nullptr, false, &joint_r,
          [&](int, int v1, int v2, const PartRows& p, int row) {
            big_->spare_.add(p.residual[row], v1, v2);
          },
          [] {});
    }
    joint_r[c] = rc;
    largest = larger_residual(largest, rc);
    big_->spare_.joint[i + 1] = big_->spare_.rows;
  }
  std::swap(big_->chord_, big_->spare_);
  return largest;
}

void Polisher::list_rows_by_body() {
  // A dense system's lists serve again while its rows join the same unknowns: the group's next
  // step, or the next group of the same shape (the 400 four-bars list theirs once).
  const auto& rows = w_->rows_;
  const bool small = dense();
  Caches& caches = w_->caches_;
  if (!small && lists_current_ && caches.of(Caches::kLists, this)) return;
  caches.drop(Caches::kLists);
  if (small && caches.listed_for(rows, nv_)) return;
  caches.drop(Caches::kListed);
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
  if (small) {
    caches.made_listed(rows, nv_);
  } else {
    caches.made(Caches::kLists, this);
    lists_current_ = true;
  }
}

bool Polisher::without_couplings(const SolverState& s) {
  if (without_couplings_ < 0) {
    without_couplings_ = 1;
    for (int c : group_->joints) {
      if (s.joints[static_cast<size_t>(c)].joint->coupling) without_couplings_ = 0;
    }
  }
  return without_couplings_ == 1;
}

}  // namespace dispcon
