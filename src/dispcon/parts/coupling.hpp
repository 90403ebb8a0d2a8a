// What the coupling parts (gear.hpp, rack_pinion.hpp, screw.hpp) share. A coupling ties turns,
// or a turn and a travel, of its two bodies by one equation
//   f = k1 theta1 + k2 theta2 + s - phase = 0,
// theta the turns (radians), s a travel (length), k the coupling's coefficients. Each is measured
// against a reference carried by the bodies themselves (the line of centres, the rack's direction,
// the nut's reference), so f is unchanged when the whole pair moves rigidly: its gradient J is
// then a pair of opposite impulses, and the correction
//   dq = -W J^T lambda,  lambda = f / (J W J^T),  W = diag(A1, mu1 I, A2, mu2 I)
// conserves the pair's first-order linear and angular momenta in the physics variant (W is the
// inverse mass times m1 m2 / (m1 + m2) there), as the seed's corrections do (footnote 5).
//
// A turn is measured wrapped into (-pi, pi]; the solver unwraps it against the last value it saw
// (coupling_value), so "the ratio holds through full turns" needs no more than the phase.
#pragma once

#include "dispcon/model/joint.hpp"
#include "dispcon/parts/part.hpp"

namespace dispcon {

// Where a body is: a local point p is at R p + x; G is its centre (the rows' rotation point).
struct Frame {
  Mat3 R = Mat3::Identity();
  Vec3 x = Vec3::Zero();
  Vec3 G = Vec3::Zero();
  Vec3 at(const Vec3& local) const { return R * local + x; }
};

// A coupling's equation at the current poses.
struct CouplingMeasure {
  int angles = 0;                              // turns in the equation (1 or 2)
  double theta[2] = {0, 0};                    // wrapped turns, (-pi, pi]
  double k[2] = {0, 0};                        // their coefficients
  double s = 0;                                // the travel term
  Row dtheta[2] = {Row::Zero(), Row::Zero()};  // gradients (when asked for)
  Row ds = Row::Zero();
  bool valid = true;  // false when a turn has no reference (it lies along the axis)
};

// The turn of r (a unit vector of a body, across its axis n) about n, measured from `ref`:
// theta = atan2((ref x r) . n, ref . r) = -atan2(ref . (n x r), ref . r). With `row`, also its
// gradient: r and n turn with the body on columns [side, side + 3), ref moves as `dref` (3 x 12).
// Returns false when ref lies along n.
bool turn(const Vec3& n, const Vec3& r, const Vec3& ref, const Eigen::Matrix<double, 3, 12>* dref,
          int side, double& theta, Row* row);

// The equation of `c` between bodies at f1 and f2 (dispatches to the part of its kind).
CouplingMeasure measure_coupling(const CouplingSpec& c, const Frame& f1, const Frame& f2,
                                 bool with_rows);

// The turn `theta` (wrapped) unwrapped next to `last` (the value seen before): the same angle
// plus the whole turns that keep it within half a turn of `last`.
double unwrap(double theta, double last);

// The turns of `m` unwrapped next to `last` into `turns`: each the short way round, but a turn
// within a few tenths of a radian of half a turn from `last` (either way round is then about as
// short: a drag step of exactly half a screw turn ends on the tie) the way round that leaves f
// nearer 0. Valid poses then unwrap onto the turn their travel asks for, whichever side of the half
// turn rounding puts them, and a solve converging there sees f continuous rather than a jump of a
// whole turn's travel where its steps cross the half turn.
void unwrap_turns(const CouplingMeasure& m, const double last[2], double phase, double turns[2]);

// The same for poses read (a solve's start, a model's new poses), which may have moved any way
// since `last`: as unwrap_turns, but where the turns taken so leave f open and a few whole turns
// more or less make it hold (to a millionth of a turn's travel: poses a solve left valid), those;
// a coupling of one turn (a screw, a rack) takes however many whole turns make it hold.
// A pull that turned a screw or a gear past half a turn from the poses last read is read back
// onto the turns it made, not a whole turn's travel open. Only from poses where it held
// (`held_before`): a gear turned by hand a whole turn, its mate left, keeps that turn in its phase
// (the turns taken the short way), though one turn less would make the equation hold.
void unwrap_read(const CouplingMeasure& m, const double last[2], double phase, double turns[2],
                 bool held_before = true);
// Whether the equation holds at `m`'s turns as measured (those last seen), to a millionth of a
// turn's travel: the test unwrap_read's `held_before` asks.
bool coupling_held(const CouplingMeasure& m, double phase);

// f with the turns unwrapped next to `last` (unwrap_turns).
double coupling_residual(const CouplingMeasure& m, const double last[2], double phase);

// The row of f (gradient of the unwrapped equation, residual f).
PartRows coupling_rows(const CouplingMeasure& m, const double last[2], double phase);

// The correction dq = -W J^T f / (J W J^T): rotations to dR1, dR2 and translations to dx1, dx2.
void coupling_corrections(const CouplingMeasure& m, const double last[2], double phase,
                          const Mobility& b1, const Mobility& b2, Vec3* dR1, Vec3* dR2, Vec3* dx1,
                          Vec3* dx2);

}  // namespace dispcon
