// Baraff and Witkin's implicit Euler for the springs, one Newton step (paper eqs. 32-36):
//   (M - dt df/dv - dt^2 df/dx) dv = dt (f0 + dt df/dx v0),   v += dv,   x += dt v
// df/dv = -(alpha m + c) I per node. Each spring's df/dx block is
//   -k [ n n^T + max(0, 1 - L0/l) (I - n n^T) ]
// with the transverse term clamped at zero for compressed springs so the matrix stays
// positive definite (the usual fix, cf. Choi and Ko 2002). The sparse matrix has a fixed
// pattern (node blocks plus one block pair per spring) built at create; each step refills its
// values in place and runs a Jacobi-preconditioned CG on preallocated vectors. (Eigen's
// ConjugateGradient allocates its four work vectors inside every solve, so the loop is ours.)
#pragma once

#include <Eigen/Sparse>
#include <cstdint>
#include <vector>

#include "tacta/model_api.h"

namespace tacta::models {

class MassSpringModel;

class BaraffWitkinSolver {
 public:
  explicit BaraffWitkinSolver(const MassSpringModel& model);
  uint32_t step(const MassSpringModel& model, tacta_body_state& state, double dt) noexcept;
  int last_iterations() const { return last_iterations_; }

 private:
  void assemble(const MassSpringModel& model, const double* x, double dt) noexcept;
  bool solve(int max_iterations, double tolerance) noexcept;

  Eigen::SparseMatrix<double> matrix_;
  std::vector<int32_t> node_slots_;    // 9 per node: value indices of the diagonal block
  std::vector<int32_t> spring_slots_;  // 36 per spring: blocks (a,a) (a,b) (b,a) (b,b)
  std::vector<double> jacobian_;       // 9 per spring: df_a/dx_b = -df_a/dx_a
  Eigen::VectorXd rhs_, dv_, residual_, preconditioned_, direction_, product_, inverse_diagonal_,
      force_;
  int last_iterations_ = 0;
};

}  // namespace tacta::models
