// The Newton polish (a group's last iterations), internal to the solver; the step in
// polish.cpp, its dense factorisation in polish_dense.cpp, its sparse one in polish_sparse.cpp.
#pragma once

#include <Eigen/Dense>
#include <memory>
#include <utility>
#include <vector>

#include "dispcon/solve/block_ldlt.hpp"
#include "dispcon/solve/group.hpp"
#include "dispcon/solve/huge_pages.hpp"
#include "dispcon/solve/pattern_cholesky.hpp"
#include "dispcon/solve/sparse_ldlt.hpp"

namespace dispcon {

// Scratch space of the Newton polish, shared by the groups of a session (they are solved one
// after another): warm after the first, so the iterations allocate nothing.
struct PolishWork {
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  // A row of J. M^-1 times its blocks is computed where it is used rather than kept: the rows of a
  // 100,000-link chain took 60 MB with it, and their first touch cost more than computing it.
  struct Entry {
    int v1 = -1, v2 = -1;  // unknowns of the two bodies, -1 when the body does not move
    Vec6 j1, j2;           // the row's two 6-blocks
  };
  HugeVector<Entry> rows_;  // tens of megabytes in the largest models
  std::vector<double> residual_;
  std::vector<int> var_start_, fill_;         // rows of body v: var_rows_[var_start_[v] ...]
  HugeVector<std::pair<int, int>> var_rows_;  // (row, side 1 or 2)
  std::vector<Vec6> dq_;
  std::vector<Vec6> u_;  // M^-1 times the blocks of one body's rows, or all rows' (row_products)
  // Plain buffers under Eigen maps: groups of different sizes share them, and an Eigen matrix
  // would reallocate at every change of size.
  std::vector<double> y_;
  std::vector<double> dense_;
  PatternCholesky chol_;  // dense_'s factorisation, its pattern kept for the next system
  Eigen::MatrixXd full_;  // the fallback LDLT's copy
  Eigen::LDLT<Eigen::MatrixXd> dense_ldlt_;
  std::vector<std::pair<int, int>> block_pairs_, column_;  // the analysis's scratch
  std::vector<int> place_;
  std::vector<int> blocks_here_, column_rows_;  // the analysis's scratch: one body, one column
  std::vector<double> rows_per_body_;
  std::vector<int> joint_rows_;  // the rows of the k-th joint with rows: joint_rows_[k] ...
  std::vector<int> block_of_, block_start_;  // the analysis's blocks (a joint's rows)
  std::vector<double> soft_;  // each row's own damping (a pull's rows), empty when none
  // Each joint's geometry (the group's i-th joint's in geometry_[i]) as a small group's measure
  // looked at it, for the chord step that may follow at the same poses (Caches::kGeometry).
  std::vector<JointGeometry> geometry_;
  // The poses of the group's bodies before the step a thread is taking (solver.cpp's iterate).
  PoseBuffer before_;
  // ... and the best poses seen of the group it runs (solver.cpp's Session::Impl::run).
  PoseBuffer best_;
  // What the buffers above hold beyond the step in hand, and for which polisher: the caches a
  // step may find again. One record, its tags set by made() and let go by drop() alone, so that
  // a cache added to the work is one more Cache here, dropped where the others are.
  class Caches {
   public:
    enum Cache : unsigned {
      // A small group's dense factorisation (dense_, u_) with its rows and row lists, for a
      // chord step.
      kChord = 1,
      // rows_ (and residual_, joint_rows_) gathered by a measure at the poses it measured, for
      // the next step.
      kRows = 2,
      // var_start_ and var_rows_: a large group's rows listed by body (see
      // Polisher::lists_current_).
      kLists = 4,
      // var_start_ and var_rows_: a dense system's, of rows joining the unknowns that
      // made_listed() was given; any polisher whose rows join the same unknowns may take them
      // (the 400 four-bars list theirs once). Tagged by those unknowns, not by an owner.
      kListed = 8,
      // geometry_, of the poses the owner's last measure() looked at.
      kGeometry = 16,
    };
    // Whether the cache (kChord, kRows, kLists or kGeometry: those tagged by an owner) was made
    // by `owner`;
    // and the cache so tagged.
    bool of(Cache c, const void* owner) const { return owner_[index(c)] == owner; }
    void made(Cache c, const void* owner) { owner_[index(c)] = owner; }
    // Whether kListed holds lists of rows joining `rows`' unknowns, of nv unknowns in all.
    template <typename Rows>
    bool listed_for(const Rows& rows, int nv) const {
      if (listed_nv_ != nv || listed_.size() != 2 * rows.size()) return false;
      size_t a = 0;
      while (a < rows.size() && rows[a].v1 == listed_[2 * a] && rows[a].v2 == listed_[2 * a + 1])
        ++a;
      return a == rows.size();
    }
    // kListed made for `rows`, of nv unknowns in all.
    template <typename Rows>
    void made_listed(const Rows& rows, int nv) {
      listed_.resize(2 * rows.size());
      for (size_t a = 0; a < rows.size(); ++a) {
        listed_[2 * a] = rows[a].v1;
        listed_[2 * a + 1] = rows[a].v2;
      }
      listed_nv_ = nv;
    }
    // Lets go of the caches in `caches` (a sum of Cache); with `owner`, only of those it made
    // (kListed, made for any polisher of the same rows, goes only without).
    void drop(unsigned caches, const void* owner = nullptr) {
      for (const Cache c : {kChord, kRows, kLists, kGeometry}) {
        const unsigned i = index(c);
        if ((caches & c) && (!owner || owner_[i] == owner)) owner_[i] = nullptr;
      }
      if ((caches & kListed) && !owner) listed_nv_ = -1;
    }

   private:
    static constexpr unsigned kOwned = 4;  // kChord, kRows, kLists, kGeometry: by their owner
    static unsigned index(Cache c) {
      return c == kChord ? 0 : c == kRows ? 1 : c == kLists ? 2 : 3;
    }
    const void* owner_[kOwned] = {};
    // kListed's rows: the unknowns of each row's two bodies (v1, v2), and the unknowns' count
    // (-1: none listed).
    std::vector<int> listed_;
    int listed_nv_ = -1;
  };
  Caches caches_;
};

// The bounds a pull has let go (pull.cpp): bit p of parts[c] for joint c's p-th part (as
// BoundTest::part numbers them); such a bound has rows in a step only when passed by more than
// -band, whatever the joint's band. Empty: none.
struct LetGo {
  std::vector<unsigned char> parts;
  double band = 0;
};

// Newton polish. The step is dq = M^-1 J^T y with (J M^-1 J^T + lambda I) y = -r: the
// displacement produced by constraint impulses J^T y, opposite on the two bodies of each joint,
// so it conserves first-order momenta like the seed's corrections; lambda regularises redundant
// rows (a planar linkage in 3D) and damps far from the solution (Levenberg-Marquardt).
// J M^-1 J^T is assembled body by body (rows sharing a body couple); small systems are factored
// dense, large ones sparse, reusing the sparse symbolic analysis while the rows keep their pattern.
class Polisher {
 public:
  explicit Polisher(const Group& group)
      : group_(&group), nv_(static_cast<int>(group.bodies.size())) {}

  // `band[c]` widens what counts as a bound in contact for joint c (see Session::solve()).
  // Returns false when no step could be computed.
  // With `reuse`, a large group in the saddle-point form may solve with the factorisation of its
  // last step instead of a new one (a chord step: the Jacobian moved little since); reused()
  // tells whether it did.
  // `measured`: the poses have not changed since the last measure().
  // `soft`, when given, damps joint c's rows by soft[c] more than lambda (relative alike): a
  // pull's rows, which the step then meets only as far as the other joints let it (the step
  // minimises |dq|_M^2 + |J_soft dq + r_soft|^2 / soft while it meets the other rows). No chord
  // step then.
  // `let_go`, when given (a pull's), the bounds it has let go.
  bool step(SolverState& s, PolishWork& work, const std::vector<double>& band, double lambda,
            double max_rotation, bool reuse, bool measured,
            const std::vector<double>* soft = nullptr, const LetGo* let_go = nullptr);
  bool reused() const { return reused_; }
  // Whether the last step left its rows' impulses y (dq = M^-1 J^T y) in the work's y_, one a
  // row in the order of the group's joints and each joint's parts: a dense or rows-form step,
  // or a pull's (given `let_go`) in the saddle-point form, whose solution holds them beside dq
  // (other saddle-point steps leave them unread).
  bool has_multipliers() const { return has_multipliers_; }
  // Whether a small group (a dense system) may take chord steps too: only where its rows leave
  // no free motion (see no_free_motion()), and only within one solve. Off unless set (a drag's
  // held solve keeps its Newton steps).
  void allow_small_chord(bool allow) { small_chord_ = allow; }
  // Whether the next chord step would be a small group's: it follows only a Newton step that
  // gained a hundredfold (near the answer, where the Jacobian moves little; further out a chord
  // step gains little, and a dense Newton step is cheap).
  bool small_chord_ready() const { return small_factored_; }
  // The factor the last step() scaled its dq by so that no body turns more than max_rotation
  // (the seed's 2.3), and whether it did (a step cut short; false for a whole step).
  double step_scale() const { return step_scale_; }
  bool cut_short() const { return cut_short_; }
  // Each joint's residual at the current poses into `joint_r` and the largest, as max_residual()
  // gives them; when a chord step may follow (a factorisation to reuse), the same pass over the
  // joints' geometry also keeps the rows' residuals, so that step need not measure again.
  // With `since_kept` (a solve's first measure), the joints whose bodies have not moved since
  // keep_measure() (their rotations and positions the same bits) are not measured again: their
  // residuals and rows' residuals are those kept. A drag's frame moves the held body only, so
  // its first measure looks at the held body's joints alone.
  double measure(const SolverState& s, const std::vector<double>& band,
                 std::vector<double>& joint_r, bool since_kept = false);
  // Keeps the last measure for the next solve's first one, when it was of the current poses
  // (measure() the last thing done); `joint_r` holds its joints' residuals.
  void keep_measure(const SolverState& s, const std::vector<double>& joint_r);

 private:
  using Vec6 = PolishWork::Vec6;
  using Entry = PolishWork::Entry;
  using Caches = PolishWork::Caches;

  // The rows of the group's joints into the work; with `joint_r`, each joint's residual too, from
  // the same look at its geometry (the largest returned).
  double gather(const SolverState& s, const std::vector<double>& band,
                const std::vector<double>* soft, const LetGo* let_go,
                std::vector<double>* joint_r = nullptr);
  // Row a's own damping beyond lambda (a pull's), in the units of the diagonal's scale.
  double soft(int a) const { return w_->soft_.empty() ? 0 : w_->soft_[static_cast<size_t>(a)]; }
  double gather_residuals(const SolverState& s, const std::vector<double>& band,
                          std::vector<double>* joint_r);
  double measure_moved(const SolverState& s, const std::vector<double>& band,
                       std::vector<double>& joint_r);
  // Inline: the dense step's row_products() call it once a row and side, where the call's own
  // cost was a third of its arithmetic.
  static Vec6 apply_inverse_mass(const BodyState& b, const Vec6& j) {
    Vec6 u;
    u.head<3>() = b.K * (b.inv_m * j.head<3>());
    u.tail<3>() = b.inv_m * j.tail<3>();
    return u;
  }
  // The state of unknown v's body (during step()).
  const BodyState& body(int v) const {
    return s_->bodies[static_cast<size_t>(group_->bodies[static_cast<size_t>(v)])];
  }
  // Lists each unknown's rows (var_start_, var_rows_, in row order), counted then placed, so
  // nothing is allocated once warm.
  void list_rows_by_body();
  // Calls f(a, b, value) for every entry a >= b of J M^-1 J^T that two rows sharing a body give,
  // body by body: the product j_a . M^-1 j_b of their blocks on that body (every group has them,
  // couplings among its joints or not: in the 400 four-bars 110 products of six terms a step).
  // Without Values, the same calls in the same order with 0 for the value: the pattern alone,
  // without the products.
  // A dense system's M^-1 J^T is kept whole (u_[p] for var_rows_[p]) for the step's dq, which
  // then need not compute it again; a large system's one body at a time (see Entry).
  template <bool Values = true, typename F>
  void row_products(F&& f) {
    list_rows_by_body();
    const bool keep = dense();
    if (keep) w_->u_.resize(static_cast<size_t>(w_->var_start_.back()));
    for (int v = 0; v < nv_; ++v) {
      const int begin = w_->var_start_[static_cast<size_t>(v)];
      const int end = w_->var_start_[static_cast<size_t>(v) + 1];
      const int base = keep ? 0 : begin;  // u_[p - base] holds row p's M^-1 j
      if (w_->u_.size() < static_cast<size_t>(end - base)) w_->u_.resize(end - base);
      [[maybe_unused]] const BodyState& b = body(v);
      for (int p = begin; p < end; ++p) {
        const auto [ra, sa] = w_->var_rows_[static_cast<size_t>(p)];
        const Entry& ea = w_->rows_[static_cast<size_t>(ra)];
        const Vec6& ja = sa == 1 ? ea.j1 : ea.j2;
        if constexpr (Values) w_->u_[static_cast<size_t>(p - base)] = apply_inverse_mass(b, ja);
        for (int q = begin; q <= p; ++q) {
          const int rb = w_->var_rows_[static_cast<size_t>(q)].first;
          if constexpr (Values) {
            f(ra, rb, ja.dot(w_->u_[static_cast<size_t>(q - base)]));
          } else {
            f(ra, rb, 0.0);
          }
        }
      }
    }
  }

  // The step's factorisation and solution: dense for small groups (polish_dense.cpp), sparse
  // above kDenseRows rows (polish_sparse.cpp).
  bool factor(const SolverState& s, double lambda);
  bool factor_dense(double lambda);
  bool no_free_motion() const;
  // no_free_motion() of the dense factor in hand, worked out once.
  bool small_without_free_motion() {
    if (small_free_ < 0) small_free_ = no_free_motion() ? 0 : 1;
    return small_free_ == 0;
  }
  bool small_residuals(const SolverState& s, const std::vector<double>& band,
                       const JointGeometry* kept);
  double measure_keeping(const SolverState& s, std::vector<double>& joint_r);
  bool factor_sparse(const SolverState& s, double lambda);
  bool without_couplings(const SolverState& s);  // see without_couplings_
  bool same_pattern() const;
  bool solve_factored();
  // The saddle-point form on blocks (polish_blocks.cpp).
  void analyze_blocks();
  bool factor_blocks(const SolverState& s, double mu);
  bool solve_blocks(const std::vector<double>& residual);
  const std::vector<double>& predict();
  void keep_first_left();
  bool blocks_multipliers();
  void analyze_rows();

  static constexpr int kDenseRows = 120;
  // The gathered system is a small one, factorised dense (polish_dense.cpp).
  bool dense() const { return w_->rows_.size() <= static_cast<size_t>(kDenseRows); }
  static constexpr int kBlockOrdering = 20000;  // unknowns from which AMD orders blocks
  const Group* group_;
  int nv_ = 0;
  PolishWork* w_ = nullptr;         // the session's scratch space, during step()
  const SolverState* s_ = nullptr;  // the state, during step()
  bool kkt_ = false;                // the sparse system is the saddle-point form
  bool factored_ = false;           // ... and its factorisation can serve a chord step
  bool reused_ = false;             // the last step was a chord step
  bool has_multipliers_ = false;    // see has_multipliers()
  double step_scale_ = 1.0;         // see step_scale()
  bool cut_short_ = false;          // see cut_short()
  bool measured_ = false;           // measure() kept the rows' residuals in big_->chord_
  bool small_chord_ = false;        // see allow_small_chord()
  // The last dense factorisation, with its damping (lambda times the diagonal's scale), may
  // serve a chord step (a solve that persists; whether it leaves free motion: small_free_, -1
  // while not worked out).
  bool small_factored_ = false;
  double small_damping_ = 0, small_scale_ = 0;
  int small_free_ = -1;
  // A chord step's right-hand side (the rows' residuals) and the bodies each row joins, which
  // must be the analysed ones (chord_). Per group, not in PolishWork: measured at the start of a
  // frame, before the groups are shared among threads.
  struct RunSlots {
    BlockLdlt::Slot diagonal, body1, body2;
  };
  struct ChordRows {
    std::vector<double> residual;
    std::vector<int> pattern;  // the unknowns of each row's two bodies
    std::vector<int> joint;    // the group's i-th joint's rows: joint[i] ... joint[i + 1] - 1
    int rows = 0;
    // Written by index into buffers sized once for the most rows the joints can have (a
    // push_back a value cost as much as the residuals' arithmetic).
    void start(size_t joints) {
      const size_t most = 3 * kPartSlots * joints;
      if (residual.size() < most) residual.resize(most), pattern.resize(2 * most);
      joint.resize(joints + 1);
      joint[0] = rows = 0;
    }
    void add(double r, int v1, int v2) {
      residual[static_cast<size_t>(rows)] = r;
      pattern[2 * static_cast<size_t>(rows)] = v1;
      pattern[2 * static_cast<size_t>(rows) + 1] = v2;
      ++rows;
    }
  };
  // What only a large group's sparse step uses, made at its first (factor_sparse()): the small
  // groups' polishers, the 400 four-bars', are a tenth of the size without it (1,064 bytes a
  // polisher, 0.4 MB for the 400, on the command's heap at its peak).
  struct Large {
    SparseLdlt ldlt_;          // the rows form, ordered (sparse_ldlt.hpp)
    ChordRows chord_, spare_;  // spare_: measure_moved()'s new rows, swapped in
    // The measure kept by keep_measure(): the bodies the group's joints join (touched_; each
    // joint's two as indices into it), their rotations and positions then (12 values a body),
    // each joint's residual and hinge points then (7 values a joint: set_hinge() moves them
    // without a new revision of the model).
    std::vector<int> touched_, joint_touched_;
    std::vector<double> kept_pose_, kept_joint_;
    std::vector<char> moved_;
    std::vector<int> order_;  // fill-reducing order of the rows: row a is unknown order_[a]
    // The saddle-point form's blocks: the bodies', then runs of up to six rows joining the same
    // two bodies; run k holds rows run_start_[k] ... run_start_[k + 1].
    BlockLdlt blocks_;
    std::vector<int> run_start_;
    std::vector<RunSlots> run_slots_;
    std::vector<BlockLdlt::Slot> body_slots_;
    std::vector<int> analyzed_pattern_;
    HugeVector<int> slots_;  // where each value of the rows form is added (factor_sparse)
    // What a solve's first chord step left (rows in chord_'s order), without what predict()
    // added to its right-hand side, in the last three solves whose first step was one on the
    // factorisation in hand (after_first_[2] the last), and how many of those are kept (0 to 3;
    // none since a new factorisation).
    std::vector<double> after_first_[3];
    int firsts_ = 0;
    std::vector<double> predicted_;  // what the solve's first chord step added, or empty
    std::vector<double> rhs_;        // that step's right-hand side, when predicted
  };
  std::unique_ptr<Large> big_;     // null until the group's first sparse step
  bool kept_ = false;              // keep_measure() kept a measure in big_ (see there)
  bool first_step_ = false;        // the next step is a solve's first (measure() since_kept)
  bool first_chord_done_ = false;  // the next measure() follows a solve's first chord step
  bool analyzed_ = false;
  // The work's row lists (var_start_, var_rows_) are of this group's analysed pattern, and the
  // rows have kept it since: a large group's step need not list them again (set by
  // factor_sparse(); they are read while the work's Caches::kLists is this polisher's).
  bool lists_current_ = false;
  // The group's joints have no coupling (whose rows may change between a measure and the next
  // step, when its turns are followed): -1 until worked out.
  int without_couplings_ = -1;
  size_t rows_hint_ = 0;  // rows of the last gather
};

}  // namespace dispcon
