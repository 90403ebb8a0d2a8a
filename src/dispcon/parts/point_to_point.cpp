#include "dispcon/parts/point_to_point.hpp"

namespace dispcon {

void point_rotations(const Vec3& P1, const Vec3& P2, const Mobility& b1, const Mobility& b2,
                     Vec3& dR1, Vec3& dR2) {
  const Vec3 d = P2 - P1;
  dR1 += b1.A * (P1 - b1.G).cross(d);
  dR2 -= b2.A * (P2 - b2.G).cross(d);
}

void point_translations(const Vec3& P1, const Vec3& P2, const Mobility& b1, const Mobility& b2,
                        Vec3& dx1, Vec3& dx2) {
  const Vec3 d = P2 - P1;
  dx1 += b1.mu * d;
  dx2 -= b2.mu * d;
}

PartRows point_rows(const Vec3& Q, const Vec3& P2, const Vec3& G1, const Vec3& G2,
                    const Nearest& nearest, bool jacobian) {
  PartRows out;
  out.count = nearest.rows;
  out.at_limit = nearest.at_limit;
  const Vec3 e = P2 - Q;
  const Vec3 r1 = Q - G1;
  const Vec3 r2 = P2 - G2;
  for (int k = 0; k < nearest.rows; ++k) {
    const Vec3& n = nearest.normals[static_cast<size_t>(k)];
    out.residual[k] = n.dot(e);
    if (!jacobian) continue;
    Row& J = out.J[k];
    // d(n . e) = n . (dR2 x r2 + dx2 - dR1 x r1 - dx1);  n . (w x r) = w . (r x n)
    J.segment<3>(0) = -r1.cross(n).transpose();
    J.segment<3>(3) = -n.transpose();
    J.segment<3>(6) = r2.cross(n).transpose();
    J.segment<3>(9) = n.transpose();
  }
  return out;
}

}  // namespace dispcon
