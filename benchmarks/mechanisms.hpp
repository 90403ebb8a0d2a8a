// Mechanisms built in code for the benchmarks, the same problem for dispcon and SolveSpace.
#pragma once

#include <vector>

#include "dispcon/model/model.hpp"

namespace bench {

// The planar crank-rocker of the samples: crank 1, coupler 3, rocker 2.5, ground 3. The crank is
// fixed at angle t; the coupler and rocker start rough. N copies, stacked along z.
struct FourBarProblem {
  double t = 0.7;
  double a = 1, b = 3, c = 2.5, d = 3;
  // Rough start of the coupler-rocker pin B (the same for both solvers).
  double bx = 2.2, by = 2.0;
};

// The same four-bar n times (the benchmark's file: its numbers repeat from copy to copy).
std::vector<FourBarProblem> fourbar_copies(int n, const FourBarProblem& p = {});
// n four-bars each of its own size, crank angle and rough start, so that no two share a number
// (lengths within 10 % of the problem's above, the crank within 0.3 rad of 0.7, the rough B
// 0.6-1.1 left and 0.3-0.7 below the pin's place on the same branch): a model whose read, solve
// and JSON find no repeats to reuse.
std::vector<FourBarProblem> fourbar_variants(int n);

dispcon::Model fourbars_dispcon(const std::vector<FourBarProblem>& problems);
inline dispcon::Model fourbars_dispcon(int n, const FourBarProblem& p = {}) {
  return fourbars_dispcon(fourbar_copies(n, p));
}
// The rocker's angle of copy k after a dispcon solve.
double rocker_angle_dispcon(const dispcon::Model& m, int k);

struct SlvsResult {
  int result = -1;
  std::vector<double> rocker;  // the rocker's angle of each copy
};
// SolveSpace at its easiest: 2D points in one workplane, distances (4 unknowns per four-bar),
// the crank's tip on a line at angle t; with `crank_angle`, the crank held by an angle
// constraint to the ground instead (the set-up: 30 times slower for SolveSpace).
SlvsResult fourbars_slvs(const std::vector<FourBarProblem>& problems, bool crank_angle = false);
inline SlvsResult fourbars_slvs(int n, const FourBarProblem& p = {}, bool crank_angle = false) {
  return fourbars_slvs(fourbar_copies(n, p), crank_angle);
}
// SolveSpace on dispcon's problem: rigid links in 3D (frames of 7 parameters each).
SlvsResult fourbars_slvs_rigid(const std::vector<FourBarProblem>& problems);
inline SlvsResult fourbars_slvs_rigid(int n, const FourBarProblem& p = {}) {
  return fourbars_slvs_rigid(fourbar_copies(n, p));
}

// A closed chain of n links, one fixed, on a circle, perturbed by 0.01.
dispcon::Model closed_chain(int n);

// A grid of coupled four-bars: rows x cols cells; neighbours share links (many closed loops).
dispcon::Model fourbar_grid(int rows, int cols);

// A train of n gears on axles fixed to the frame, along x, pitch radii alternating 1 and 0.5,
// each meshing the next (a gear coupling of ratio r_i / r_(i+1)); all at turn 0.
dispcon::Model gear_train(int n);

// The FreeCAD GUI test's 100-part drag (tests/freecad/gui_drag.py's crank_chain): `cranks` cranks
// of length 1 pinned 1.5 apart along x to a fixed ground plate, turned 60 degrees, each pair of
// neighbours joined by a coupler of length 1.5 (alternate couplers one layer higher); revolutes
// about z. 2 * cranks bodies with the ground, one degree of freedom. Coupler k is body
// "coupler<k>".
dispcon::Model crank_chain(int cranks);

}  // namespace bench
