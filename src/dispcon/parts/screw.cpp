#include "dispcon/parts/screw.hpp"

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

CouplingMeasure measure_screw(const CouplingSpec& c, const Frame& f1, const Frame& f2,
                              bool with_rows) {
  CouplingMeasure m;
  m.angles = 1;
  m.k[0] = -(c.left ? -1 : 1) * c.value / (2 * kPi);
  const Vec3 C1 = f1.at(c.c1), C2 = f2.at(c.c2);
  const Vec3 n = f1.R * c.a1;
  const Vec3 r1 = f1.R * any_perpendicular(c.a1);
  m.s = (C2 - C1).dot(n);
  Eigen::Matrix<double, 3, 12> dr1 = Eigen::Matrix<double, 3, 12>::Zero();
  dr1.block<3, 3>(0, 0) = -skew(r1);
  m.valid = turn(f2.R * c.a2, f2.R * any_perpendicular(c.a2), r1, with_rows ? &dr1 : nullptr, 6,
                 m.theta[0], with_rows ? &m.dtheta[0] : nullptr);
  if (with_rows) {
    m.ds.segment<3>(0) = -((C2 - f1.G).cross(n)).transpose();
    m.ds.segment<3>(3) = -n.transpose();
    m.ds.segment<3>(6) = ((C2 - f2.G).cross(n)).transpose();
    m.ds.segment<3>(9) = n.transpose();
  }
  return m;
}

}  // namespace dispcon
