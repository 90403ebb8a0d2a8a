// Gear and belt couplings (issue 11): object2's turn about its axis is -ratio (gear, external
// mesh) or +ratio (belt, chain, internal mesh) times object1's turn about its axis.
//
// Axes: n_i = R_i a_i through C_i = R_i c_i + x_i. Each turn is measured from the line of centres
// d = C2 - C1 to r_i = R_i b_i (b_i a fixed unit vector across a_i):
//   theta_i = atan2((d x r_i) . n_i, d . r_i)
// and the coupling holds
//   gear: ratio theta1 + theta2 = phase        belt: -ratio theta1 + theta2 = phase.
// Measured from the line of centres, each turn is the turn relative to whatever carries both
// axes (the frame, or a planetary carrier: the carrier's turn drops out, which is Willis'
// formula), and it is the rolling condition of two pitch circles even when the centres move.
// Both turns move with the pair as a whole, so the row J = ratio d theta1 + d theta2 is a pair of
// opposite impulses (coupling.hpp) and the correction conserves first-order momenta.
// Row: ratio d theta1 + d theta2 (or -ratio), with m_i = n_i x r_i, x_i = d . r_i, y_i = d . m_i,
//   d theta_i = -[dR_i . (x_i m_i x d - y_i r_i x d) + (x_i m_i - y_i r_i) . dd] / (x_i^2 + y_i^2)
//   dd = dR2 x (C2 - G2) + dx2 - dR1 x (C1 - G1) - dx1
// (the body's own turn about n_i, and the swing of the line of centres; turn() in coupling.cpp).
// The line of centres must not lie along an axis (concentric gears have no mesh to measure).
#pragma once

#include "dispcon/parts/coupling.hpp"

namespace dispcon {

CouplingMeasure measure_gear(const CouplingSpec& c, const Frame& f1, const Frame& f2,
                             bool with_rows);

}  // namespace dispcon
