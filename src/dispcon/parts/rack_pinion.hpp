// Rack and pinion coupling (issue 11): the rack's travel along its direction is the pinion's
// radius times the pinion's turn.
//
// Object1 is the pinion: axis n = R1 a1 through C = R1 c1 + x1, reference r = R1 b1 (b1 a fixed
// unit vector across a1). Object2 is the rack: direction u = R2 a2, a point P = R2 c2 + x2.
//   travel  s = (P - C) . u
//   turn    theta = atan2((u x r) . n, u . r)      (from the rack's direction, so relative to
//                                                  whatever carries both)
//   s - radius theta = phase.
// Row: ds - radius d theta with
//   ds = -dR1 . ((C - G1) x u) - u . dx1 + dR2 . ((C - G2) x u) + u . dx2
// (the rack's turn swings u about C; its translation and the pinion's move P - C), and d theta
// from turn() with du = dR2 x u. Both s and theta move with the pair as a whole, so the
// correction is a pair of opposite impulses (coupling.hpp).
#pragma once

#include "dispcon/parts/coupling.hpp"

namespace dispcon {

CouplingMeasure measure_rack_pinion(const CouplingSpec& c, const Frame& f1, const Frame& f2,
                                    bool with_rows);

}  // namespace dispcon
