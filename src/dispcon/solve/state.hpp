// The solver's working copy of a model: world-frame body states and per-joint parameters, laid
// out flat so the iteration allocates nothing. Internal to the engine (solver, Jacobian,
// dynamics, diagnostics).
#pragma once

#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/parts/coupling.hpp"
#include "dispcon/parts/nearest.hpp"
#include "dispcon/parts/part.hpp"
#include "dispcon/solve/huge_pages.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {

// What a body needs during a solve, and no more: the largest models hold a hundred thousand of
// these, which every pass of the iteration reads (416 bytes a body before the physics-only
// inertia and the Jacobi iteration's sums left it, 288 now).
// The nearest point of a joint's set to p, and the directions it constrains there (seed 4.1),
// all in object1's frame: the point p1 itself without a guide, else the guide's set about p1.
Nearest nearest_on_guide(const Vec3& p1, const Guide* guide, const Vec3& p, BoundTest bound = {});

struct BodyState {
  Quat q = Quat::Identity();
  Mat3 R = Mat3::Identity();
  Vec3 x = Vec3::Zero();
  Vec3 c = Vec3::Zero();      // centre, local
  Vec3 G = Vec3::Zero();      // centre, world
  Mat3 K = Mat3::Identity();  // m J^-1 or k I, world frame
  double m = 1;               // mass (1 without physics)
  double inv_m = 1;           // 1 / m, so the polish multiplies
  // The body's inertia J in its own frame, with physics only (the model's: the state, like its
  // joints, lives no longer than its model).
  const Mat3* inertia_local = nullptr;
  int n = 0;       // active joints on this body (seed 3.2's n_i)
  int n_var = -1;  // index among the unknowns of the Newton polish
  bool movable = false;
  bool physics = false;  // K = m J^-1 (world) rather than k I

  void set_pose(const Pose& pose);
  Pose pose() const { return Pose{q, x}; }
  // Turns the body by the rotation vector dR about its centre, then moves the centre by dx.
  void displace(const Vec3& dR, const Vec3& dx);
  // Rotation per unit moment for the Newton metric: J^-1 (physics) or k (no physics, m = 1).
  Mat3 inverse_inertia() const { return K * inv_m; }
};

struct JointState {
  const Joint* joint = nullptr;
  int b1 = 0, b2 = 0;  // body indices
  double mu1 = 0.5;    // body 1's share of a translation
  double mu2 = 0.5;
  double w = 1;  // seed 3.2 weight 1/max(n_i, n_j) times the relaxation
  bool active = true;
  bool bounded = false;  // has a bound that can be in contact (segment end, angle limit, ...)
  // A coupling's phase and the turns last seen, against which its turns are unwrapped: both move
  // on together whenever poses are read (read_poses), so full turns are counted.
  double phase = 0;
  double last[2] = {0, 0};
};

// The parts of a joint, in the order they give rows: translation, angle, twist, coupling.
constexpr int kPartSlots = 4;

// A joint's bound test part by part: `bound` for every part but those a pull has let go (bit p
// for its p-th part, in the order its rows come: translation, angle, twist, coupling), whose
// bounds count only when passed by more than -let_go (pull.cpp). The parts take the one
// BoundTest meant for them (a double, in a register).
struct JointBounds {
  BoundTest bound;
  unsigned let_go_parts = 0;
  double let_go = 0;
  BoundTest part(int p) const { return (let_go_parts >> p & 1u) != 0 ? BoundTest{let_go} : bound; }
};

// A joint's geometry at the current poses, world frame.
struct JointGeometry {
  bool translation = false;
  Vec3 Q = Vec3::Zero();   // nearest permissible point of object1's guide
  Vec3 P2 = Vec3::Zero();  // object2's point
  Nearest nearest;         // normals in world frame
  Vec3 a1, a2, b1, b2;     // world axes of angle and twist parts (when present)
};

// How close to a bound counts as "in contact" in reports and diagnostics: the tolerance, but not
// below 1e-7, since a converged solve may leave a joint anywhere within the tolerance of its bound.
inline double contact_band(double tolerance) {
  return tolerance > 1e-7 ? tolerance : 1e-7;
}

class SolverState {
 public:
  SolverState(const Model& model, const std::vector<Pose>& poses, const SolveOptions& options,
              const std::vector<bool>& held);

  HugeVector<BodyState> bodies;  // tens of megabytes in the largest models
  std::vector<JointState> joints;
  // The Jacobi iteration's sums of the proposals of one iteration, per body (sized only when
  // the options ask for that scheme).
  std::vector<Vec3> proposed_turn, proposed_move;

  void write_poses(std::vector<Pose>& poses) const;
  // Reads new poses; each coupling's turns are unwrapped next to the last ones seen.
  void read_poses(const std::vector<Pose>& poses);

  Mobility mobility(const JointState& js, int side) const;
  JointGeometry geometry(const JointState& js, BoundTest bound = {}) const;
  // Largest violation of a joint's parts (length units or radians); 0 when inactive.
  double residual(const JointState& js) const;
  bool at_limit(const JointState& js, double band) const;
  // The rotations one joint proposes, unweighted (seed 4.2.3 order): the translation part's
  // eq. 18, then the angle part on the axes as they would be after those, then the twist part.
  void propose_rotations(const JointState& js, Vec3& dR1, Vec3& dR2) const;
  // The translations one joint proposes from the current poses (eq. 19 after rotation).
  void propose_translations(const JointState& js, Vec3& dx1, Vec3& dx2) const;
  // Appends the rows of one joint (translation part, angle, twist, coupling) to `out`; without
  // J when `jacobian` is false (the rows' residuals alone).
  void rows(const JointState& js, BoundTest bound, PartRows out[kPartSlots],
            bool jacobian = true) const {
    rows(js, JointBounds{bound}, out, jacobian);
  }
  // The same, with bounds a pull has let go.
  void rows(const JointState& js, const JointBounds& bounds, PartRows out[kPartSlots],
            bool jacobian = true) const;
  // rows() and residual() together, from one look at the joint's geometry where both see the
  // same (the nearest point of a guide without ends does not depend on the bound test).
  double rows_and_residual(const JointState& js, BoundTest bound, PartRows out[kPartSlots],
                           bool jacobian) const;
  // residual(), its look at the joint's geometry kept in `g` (built there, not copied), for
  // rows_from() at the same poses.
  double residual_keeping(const JointState& js, JointGeometry& g) const;
  // Whether a joint's geometry is the same whatever the bound test: every joint's but those on a
  // guide with ends, whose nearest point depends on the band.
  static bool geometry_without_bounds(const JointState& js) {
    const Guide* guide = js.joint->guide ? &*js.joint->guide : nullptr;
    return !guide || guide->kind == GuideKind::Point || guide->kind == GuideKind::Circle;
  }
  // rows() from the geometry residual_keeping() kept at the current poses: the same rows, without
  // looking at the geometry again (only where geometry_without_bounds()).
  void rows_from(const JointState& js, const JointGeometry& g, BoundTest bound,
                 PartRows out[kPartSlots], bool jacobian) const {
    rows_at(js, g, JointBounds{bound}, out, jacobian);
  }
  // For each row rows() gives a joint (the same test), the component along it of the way out of
  // the bound its part rests on, the direction that passes that bound: +1 for an angle's or a
  // twist's upper bound, -1 for a lower one; a guide's rows' normals dotted with the way out of
  // its set at the end the point rests on. 0 for the rows of parts at no bound. An impulse y on
  // the rows moves them by a positive multiple of y, so sum_k y_k out[p][k] > 0 says the part's
  // rows push it out past its bound: the rest of the step would take it back inside.
  void outward(const JointState& js, const JointBounds& bounds, double out[kPartSlots][3]) const;
  // A coupling's equation at the current poses (the joint must have one).
  CouplingMeasure coupling(const JointState& js, bool with_rows) const;
  // The couplings among `joints` take their turns at the current poses as the last seen (each
  // moved on the short way round, as unwrap_turns takes it): a pull's kept step, so that a pull
  // turning a screw on and on sees each of its steps near the last (read_poses alone would put
  // the way round's change at half a turn from the poses read, where the pull would stop).
  void follow_couplings(const std::vector<int>& joints);

 private:
  void unwrap_couplings();
  double residual_at(const JointState& js, const JointGeometry& g) const;
  void rows_at(const JointState& js, const JointGeometry& g, const JointBounds& bounds,
               PartRows out[kPartSlots], bool jacobian) const;
};

}  // namespace dispcon
