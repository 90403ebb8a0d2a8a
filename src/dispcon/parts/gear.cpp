#include "dispcon/parts/gear.hpp"

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

CouplingMeasure measure_gear(const CouplingSpec& c, const Frame& f1, const Frame& f2,
                             bool with_rows) {
  CouplingMeasure m;
  m.angles = 2;
  m.k[0] = c.kind == CouplingKind::Belt ? -c.value : c.value;
  m.k[1] = 1;
  const Vec3 C1 = f1.at(c.c1), C2 = f2.at(c.c2);
  const Vec3 d = C2 - C1;
  // d(d) = dR2 x (C2 - G2) + dx2 - dR1 x (C1 - G1) - dx1.
  Eigen::Matrix<double, 3, 12> dd;
  dd << skew(C1 - f1.G), -Mat3::Identity(), -skew(C2 - f2.G), Mat3::Identity();
  const auto* dref = with_rows ? &dd : nullptr;
  m.valid = turn(f1.R * c.a1, f1.R * any_perpendicular(c.a1), d, dref, 0, m.theta[0],
                 with_rows ? &m.dtheta[0] : nullptr) &&
            turn(f2.R * c.a2, f2.R * any_perpendicular(c.a2), d, dref, 6, m.theta[1],
                 with_rows ? &m.dtheta[1] : nullptr);
  return m;
}

}  // namespace dispcon
