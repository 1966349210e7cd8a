// Desbrun, Schröder and Barr (1999), "Interactive animation of structured deformable objects":
// the springs' force splits into a linear part, -L_k x (zero-rest-length springs, L_k the
// k-weighted graph Laplacian, the same for x, y and z), and a non-linear rest-length part. The
// linear part is integrated implicitly with a matrix fixed for the whole run,
//   (M (1 + dt alpha) + dt c + dt^2 L_k) dv = dt (f(x) + f_ext - C v - dt L_k v),
// factorised once (n x n, shared by the three coordinates). The non-linear part enters only
// through f(x). Filtering f through this inverse changes the body's angular momentum although
// the spring forces are central; the correction removes that change with a rigid rotation
// (omega = I^-1 dL, dv_i -= omega x r_i), applied when no node is fixed.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <cstdint>

#include "tacta/model_api.h"

namespace tacta::models {

class MassSpringModel;

class DesbrunSolver {
 public:
  DesbrunSolver(const MassSpringModel& model, double dt);
  void step(const MassSpringModel& model, tacta_body_state& state, double dt) noexcept;

 private:
  void solve_in_place(Eigen::VectorXd& column) noexcept;
  void correct_angular_momentum(const MassSpringModel& model, const tacta_body_state& state,
                                double dt) noexcept;

  Eigen::SparseMatrix<double> laplacian_;  // L_k, N/m
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor_;
  Eigen::VectorXd inverse_d_;  // 1 / D of the factor (vectorD() returns a copy)
  Eigen::VectorXd force_, column_, permuted_, velocity_column_, laplacian_v_;
  Eigen::VectorXd dv_;  // 3 per node
  bool any_fixed_ = false;
};

}  // namespace tacta::models
