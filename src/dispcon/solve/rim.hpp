// A turn's reduced quasi-Newton step (rim.cpp), internal to the pull (pull.cpp): where the held
// body slides along a cone's or a twist's rim, the pull's damped steps converge linearly (one
// damping number for the Lagrangian's curvature, which the bounds' own curvature times their
// multipliers makes indefinite). This models the objective on the few free directions the
// held rows leave, with its curvature measured from the kept steps.
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "dispcon/solve/group.hpp"
#include "dispcon/solve/polish.hpp"

namespace dispcon {

// The pull's objective h = |r_soft|^2 / 2 on the valid poses, near one: its gradient projected on
// the null space Z of the hard rows (every other joint's, held bounds included), and a BFGS model B
// of its Hessian there (the Lagrangian's, reduced: the Gauss-Newton term plus the rows' curvature
// times their multipliers), built from the pairs of kept poses (the displacement between them and
// the change of the reduced gradient). Z is carried from pose to pose (rotated to the nearest
// basis of the new null space), and the model starts again when the held rows change.
class RimModel {
 public:
  using Vec6 = PolishWork::Vec6;

  // Groups of more bodies are left to the damped steps (a dense SVD a kept step).
  static constexpr size_t kMostBodies = 12;
  // And poses with more free directions: most of a free linkage's directions barely move h (the
  // monocycle's parts, the otary's), a few pairs do not tell their curvature, and BFGS keeps its
  // model positive definite: with 6 free directions the monocycle's left foot turned 2.5 rad
  // about z was led to a saddle (a curvature of -7.9e-5 there by central differences) 0.019 rad
  // farther than where the damped steps end. A wrist's rim leaves 2 (the robot arm's hand).
  static constexpr int kMostFree = 5;

  // At a kept, valid pose: reads the rows (those a pull step would have: `band`, `let_go`, the
  // soft joint `joint` at `soft_band`) and adds the pair from the last pose observed to the model.
  // False when the group is too large or its rows unreadable (nothing kept then).
  bool observe(const SolverState& s, const Group& group, int joint, const std::vector<double>& band,
               double soft_band, const LetGo& let_go);
  // The model's step from the pose last observed: dq (one 6-vector a body, as the polisher's),
  // and the decrease of h its model predicts. False when the model has no pair yet or its step
  // does not go down. The step is held to the trust radius and to `max_rotation` a body.
  bool propose(double max_rotation, std::vector<Vec6>& dq, double& predicted) const;
  // The decrease of h the model's whole step (not held to the trust radius) predicts: infinite when
  // it has none.
  double whole_gain() const;
  // What the step proposed did (`ratio`: the decrease of h over the predicted one): a step that
  // was not kept, or gained less than a tenth of the prediction, sets the trust radius to a
  // quarter of its length; one that gained more than half of it doubles the radius it met.
  void judge(double ratio, bool kept);
  // Whether a step of the model (since its last start) gained as it predicted, within a factor
  // of two.
  bool validated() const { return validated_; }
  // Whether the last step proposed was cut short to max_rotation.
  bool cut_short() const { return cut_short_; }
  // Forget the pairs (a new pull).
  void reset();

 private:
  // Every matrix here has a fixed capacity (Eigen's maximum sizes: no heap behind them), so that
  // a turn's steps allocate nothing once the model is made (they made 261-311 allocations a drag
  // step in dynamic matrices until issue 14's fifteenth round). The capacity's largest
  // dimension, 72, keeps Eigen's products on the paths they took with dynamic sizes (below 8
  // it picks others, with other rounding).
  static constexpr int kMostUnknowns = 6 * static_cast<int>(kMostBodies);
  // The hard rows a fixed-capacity QR takes (twice the unknowns); more go to qr_wide_, which
  // allocates (no sample nor test comes near).
  static constexpr int kMostHardRows = 2 * kMostUnknowns;
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                               kMostUnknowns, kMostUnknowns>;
  using Vector = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMostUnknowns, 1>;
  using Rows = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, kMostUnknowns,
                             kMostHardRows>;
  // Q's last columns (the null space of the rows a QR was given), Q applied reflector by
  // reflector as Eigen's unblocked product does.
  template <typename QR>
  void null_space(const QR& qr, Eigen::Index n, Eigen::Index rank);

  Matrix Z_;                   // basis of the free directions at the pose last observed (columns)
  Matrix B_;                   // the reduced Hessian's model (empty: no pair yet)
  Vector gz_;                  // Z^T grad h there
  std::vector<Mat3> R_;        // each body's rotation there
  std::vector<Vec3> G_;        // and centre
  double radius_ = 0;          // the trust radius of |Z^T dq| (0: none)
  mutable double length_ = 0;  // |Z^T dq| of the last step proposed
  mutable bool cut_short_ = false;
  bool validated_ = false;
  bool observed_ = false;
  // observe()'s scratch: the hard rows, the soft ones, the gradient, the QR, the new basis, ...
  Eigen::MatrixXd hard_, soft_j_;  // sized by the group's joints: the same from step to step
  Eigen::VectorXd g_;
  Eigen::ColPivHouseholderQR<Rows> qr_;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr_wide_;
  Eigen::Matrix<double, 1, Eigen::Dynamic, Eigen::RowMajor, 1, kMostUnknowns> reflect_;
  Matrix Zn_, js_, gauss_newton_;
  Vector gzn_, step_, sz_, y_, bs_;
  Eigen::JacobiSVD<Matrix> svd_;
  // ... and propose()'s and whole_gain()'s.
  mutable Eigen::LLT<Matrix> llt_;
  mutable Vector p_, full_;
};

}  // namespace dispcon
