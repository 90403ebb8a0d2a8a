// The constraints' Jacobian, for the Newton polish and for diagnostics (DOF, redundancy).
//
// Columns: 6 per body (index = BodyId::value): the small rotation vector about the body's centre
// and the small translation of that centre, both in world coordinates (the seed's dR and dx).
// Rows: one per constrained direction of every active joint part; a bound contributes rows only
// when it is violated or in contact (within the tolerance).
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "dispcon/model/model.hpp"
#include "dispcon/solve/solver.hpp"

namespace dispcon {

enum class PartKind { Translation, Angle, Twist, Coupling };

struct JacobianRow {
  JointId joint;
  PartKind part = PartKind::Translation;
  bool limit = false;   // this row comes from a bound in contact or violated
  double residual = 0;  // signed value of this row's constraint function
};

struct ConstraintJacobian {
  Eigen::SparseMatrix<double, Eigen::RowMajor> J;  // rows x (6 * body_count)
  Eigen::VectorXd residual;                        // one per row
  std::vector<JacobianRow> rows;
};

ConstraintJacobian constraint_jacobian(const Model& model, const std::vector<Pose>& poses,
                                       const SolveOptions& options);

}  // namespace dispcon
