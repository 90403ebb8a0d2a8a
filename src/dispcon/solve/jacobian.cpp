#include "dispcon/solve/jacobian.hpp"

#include "dispcon/solve/state.hpp"

namespace dispcon {

ConstraintJacobian constraint_jacobian(const Model& model, const std::vector<Pose>& poses,
                                       const SolveOptions& options) {
  const SolverState s(model, poses, options, {});
  ConstraintJacobian out;
  std::vector<Eigen::Triplet<double>> triplets;
  std::vector<double> residual;
  PartRows parts[kPartSlots];
  const PartKind kinds[kPartSlots] = {PartKind::Translation, PartKind::Angle, PartKind::Twist,
                                      PartKind::Coupling};
  int row = 0;
  for (size_t c = 0; c < s.joints.size(); ++c) {
    const JointState& js = s.joints[c];
    if (!js.active) continue;
    s.rows(js, BoundTest{contact_band(options.tolerance)}, parts);
    for (int p = 0; p < kPartSlots; ++p) {
      for (int k = 0; k < parts[p].count; ++k) {
        for (int col = 0; col < 12; ++col) {
          const double v = parts[p].J[k](col);
          if (v == 0) continue;
          const int body = col < 6 ? js.b1 : js.b2;
          triplets.emplace_back(row, 6 * body + col % 6, v);
        }
        residual.push_back(parts[p].residual[k]);
        JacobianRow info;
        info.joint = JointId{static_cast<int>(c)};
        info.part = kinds[p];
        info.limit = parts[p].at_limit;
        info.residual = parts[p].residual[k];
        out.rows.push_back(info);
        ++row;
      }
    }
  }
  out.J.resize(row, 6 * model.body_count());
  out.J.setFromTriplets(triplets.begin(), triplets.end());
  out.residual = Eigen::Map<const Eigen::VectorXd>(residual.data(), row);
  return out;
}

}  // namespace dispcon
