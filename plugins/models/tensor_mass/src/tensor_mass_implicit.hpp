// Implicit Euler for the tensor-mass model, one linear solve per step (the model is linear):
//   (M + dt C + dt^2 K) dv = dt (F(x) + F_ext - C v - dt K v),  v += dv,  x += dt v
// with C = alpha M + beta K + c I. The matrix is assembled from the model's K_ii / K_ij blocks
// and factorised (Eigen SimplicialLDLT) once at create, for the setup's dt. Fixed nodes get
// identity rows and columns (dv = 0). The solve is done with the factor's triangular parts on
// preallocated vectors, because Eigen's solve() and permutation products allocate.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <cstdint>
#include <vector>

#include "tacta/model_api.h"

namespace tacta::models {

class TensorMassModel;

class ImplicitEulerSolver {
 public:
  ImplicitEulerSolver(const TensorMassModel& model, const std::vector<double>& mass,
                      const std::vector<uint8_t>& fixed, const tacta_material& material,
                      double damping, double dt);
  uint32_t step(const TensorMassModel& model, tacta_body_state& state, double dt) noexcept;
  double factorised_dt() const { return dt_; }

 private:
  const std::vector<double>& mass_;
  const std::vector<uint8_t>& fixed_;
  double alpha_, beta_, damping_, dt_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> factor_;
  Eigen::VectorXd inverse_d_;  // 1 / D of the factor (vectorD() returns a copy)
  Eigen::VectorXd rhs_, permuted_, dv_, force_, stiffness_v_;
};

}  // namespace tacta::models
