// The four-bars posed to SolveSpace as rigid bodies in 3D, the problem dispcon solves and an
// assembly workbench on SolveSpace has to pose: each moving link is a frame (a workplane whose
// origin and quaternion normal are unknowns, 7 parameters, the quaternion kept unit by
// SolveSpace), and the link's points are 2D points of that frame with constant coordinates, so
// they move rigidly with it. Without redundant equations (SolveSpace refuses them): each link
// keeps three points in the base plane (its plane is the base plane: 3 equations) and the pins
// coincide within that plane (2 equations each): 2 x 3 + 3 x 2 = 12 equations for 12 degrees
// of freedom.
#include <cmath>
#include <string>
#include <vector>

#include "mechanisms.hpp"
#include "slvs_include.hpp"

namespace bench {

SlvsResult fourbars_slvs_rigid(const std::vector<FourBarProblem>& problems) {
  const int n = static_cast<int>(problems.size());
  std::vector<Slvs_Param> param;
  std::vector<Slvs_Entity> entity;
  std::vector<Slvs_Constraint> constraint;
  Slvs_hParam hp = 1;
  Slvs_hEntity he = 1;
  Slvs_hConstraint hc = 1;
  const Slvs_hGroup g1 = 1, g2 = 2;  // constants; unknowns
  auto value = [&](Slvs_hGroup g, double v) {
    param.push_back(Slvs_MakeParam(hp, g, v));
    return hp++;
  };
  auto point3 = [&](Slvs_hGroup g, double x, double y, double z) {
    const Slvs_hParam a = value(g, x), b = value(g, y), c = value(g, z);
    entity.push_back(Slvs_MakePoint3d(he, g, a, b, c));
    return he++;
  };
  // A frame turned by `angle` about z: the quaternion (cos a/2, 0, 0, sin a/2).
  auto frame = [&](Slvs_hGroup g, double x, double y, double angle) {
    const Slvs_hEntity origin = point3(g, x, y, 0);
    const Slvs_hParam qw = value(g, std::cos(angle / 2)), qx = value(g, 0), qy = value(g, 0),
                      qz = value(g, std::sin(angle / 2));
    const Slvs_hEntity normal = he++;
    entity.push_back(Slvs_MakeNormal3d(normal, g, qw, qx, qy, qz));
    const Slvs_hEntity plane = he++;
    entity.push_back(Slvs_MakeWorkplane(plane, g, origin, normal));
    return std::make_pair(plane, origin);
  };
  // A point fixed on a frame: constant coordinates (u, v) in it.
  auto on = [&](Slvs_hEntity plane, double u, double v) {
    const Slvs_hParam a = value(g1, u), b = value(g1, v);
    entity.push_back(Slvs_MakePoint2d(he, g2, plane, a, b));
    return he++;
  };
  const Slvs_hEntity base = frame(g1, 0, 0, 0).first;
  auto in_plane = [&](Slvs_hEntity point) {
    constraint.push_back(
        Slvs_MakeConstraint(hc++, g2, SLVS_C_PT_IN_PLANE, SLVS_FREE_IN_3D, 0, point, 0, base, 0));
  };
  auto pin = [&](Slvs_hEntity a, Slvs_hEntity b) {
    constraint.push_back(
        Slvs_MakeConstraint(hc++, g2, SLVS_C_POINTS_COINCIDENT, base, 0, a, b, 0, 0));
  };
  std::vector<Slvs_hParam> rocker_q;  // first quaternion parameter of each rocker
  for (int k = 0; k < n; ++k) {
    const double ox = 10.0 * k;  // copies side by side (the problems are independent)
    const FourBarProblem& p = problems[static_cast<size_t>(k)];
    const double ax = ox + p.a * std::cos(p.t), ay = p.a * std::sin(p.t);
    const double bx = ox + p.bx, by = p.by, dx = ox + p.d;
    const Slvs_hEntity A = point3(g1, ax, ay, 0);  // the crank's tip: the crank is fixed
    const Slvs_hEntity D = point3(g1, dx, 0, 0);   // the rocker's ground pivot
    // The same rough start as dispcon's: each link at its first pin, pointing at the rough B.
    const auto [coupler, coupler_origin] = frame(g2, ax, ay, std::atan2(by - ay, bx - ax));
    const Slvs_hEntity coupler_b = on(coupler, p.b, 0);
    const Slvs_hEntity coupler_side = on(coupler, 0, 1);
    rocker_q.push_back(hp + 3);  // the rocker frame's origin takes 3 parameters first
    const auto [rocker, rocker_origin] = frame(g2, dx, 0, std::atan2(by, bx - dx));
    const Slvs_hEntity rocker_b = on(rocker, p.c, 0);
    const Slvs_hEntity rocker_side = on(rocker, 0, 1);
    for (Slvs_hEntity e :
         {coupler_origin, coupler_b, coupler_side, rocker_origin, rocker_b, rocker_side}) {
      in_plane(e);
    }
    pin(A, coupler_origin);
    pin(coupler_b, rocker_b);
    pin(D, rocker_origin);
  }
  SlvsResult out;
  out.result = solve_slvs(param, entity, constraint, g2);
  for (Slvs_hParam h : rocker_q) {
    const double w = param[h - 1].val, x = param[h].val, y = param[h + 1].val, z = param[h + 2].val;
    // The rocker frame's x axis, rotated by the quaternion.
    out.rocker.push_back(std::atan2(2 * (x * y + w * z), w * w + x * x - y * y - z * z));
  }
  return out;
}

}  // namespace bench
