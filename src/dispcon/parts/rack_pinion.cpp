#include "dispcon/parts/rack_pinion.hpp"

#include "dispcon/parts/nearest.hpp"

namespace dispcon {

CouplingMeasure measure_rack_pinion(const CouplingSpec& c, const Frame& f1, const Frame& f2,
                                    bool with_rows) {
  CouplingMeasure m;
  m.angles = 1;
  m.k[0] = -c.value;
  const Vec3 C = f1.at(c.c1), P = f2.at(c.c2);
  const Vec3 u = f2.R * c.a2;
  m.s = (P - C).dot(u);
  Eigen::Matrix<double, 3, 12> du = Eigen::Matrix<double, 3, 12>::Zero();
  du.block<3, 3>(0, 6) = -skew(u);
  m.valid = turn(f1.R * c.a1, f1.R * any_perpendicular(c.a1), u, with_rows ? &du : nullptr, 0,
                 m.theta[0], with_rows ? &m.dtheta[0] : nullptr);
  if (with_rows) {
    m.ds.segment<3>(0) = -((C - f1.G).cross(u)).transpose();
    m.ds.segment<3>(3) = -u.transpose();
    m.ds.segment<3>(6) = ((C - f2.G).cross(u)).transpose();
    m.ds.segment<3>(9) = u.transpose();
  }
  return m;
}

}  // namespace dispcon
