#include "tensor_mass_implicit.hpp"

#include <stdexcept>

#include "tensor_mass_model.hpp"

namespace tacta::models {

ImplicitEulerSolver::ImplicitEulerSolver(const TensorMassModel& model,
                                         const std::vector<double>& mass,
                                         const std::vector<uint8_t>& fixed,
                                         const tacta_material& material, double damping, double dt)
    : mass_(mass),
      fixed_(fixed),
      alpha_(material.rayleigh_mass),
      beta_(material.rayleigh_stiffness),
      damping_(damping),
      dt_(dt) {
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(model.node_count());
  const double k_scale = dt * dt + dt * beta_;  // dt^2 K + dt beta K
  std::vector<Eigen::Triplet<double>> entries;
  auto add_block = [&](uint32_t a, uint32_t b, const Eigen::Matrix3d& block) {
    if (fixed_[a] || fixed_[b]) return;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) entries.emplace_back(3 * a + r, 3 * b + c, k_scale * block(r, c));
  };
  for (uint32_t i = 0; i < model.node_count(); ++i) {
    add_block(i, i, model.vertex_blocks()[i]);
    const double diagonal =
        fixed_[i] ? 1.0 : mass_[i] * (1.0 + dt * alpha_) + dt * damping_;  // M + dt (alpha M + c)
    for (int c = 0; c < 3; ++c) entries.emplace_back(3 * i + c, 3 * i + c, diagonal);
  }
  for (size_t e = 0; e < model.edge_blocks().size(); ++e) {
    const uint32_t a = model.edges()[2 * e], b = model.edges()[2 * e + 1];
    add_block(a, b, model.edge_blocks()[e]);
    add_block(b, a, model.edge_blocks()[e].transpose());
  }
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(entries.begin(), entries.end());
  factor_.compute(matrix);
  if (factor_.info() != Eigen::Success)
    throw std::invalid_argument(
        "tensor_mass: implicit matrix M + dt C + dt^2 K is not positive definite");
  inverse_d_ = factor_.vectorD().cwiseInverse();
  rhs_.setZero(n);
  permuted_.setZero(n);
  dv_.setZero(n);
  force_.setZero(n);
  stiffness_v_.setZero(n);
}

uint32_t ImplicitEulerSolver::step(const TensorMassModel& model, tacta_body_state& state,
                                   double dt) noexcept {
  double* x = state.positions;
  double* v = state.velocities;
  model.internal_forces(x, force_.data());
  model.apply_stiffness(v, stiffness_v_.data());
  for (uint32_t i = 0; i < model.node_count(); ++i)
    for (uint32_t c = 3 * i; c < 3 * i + 3; ++c)
      rhs_[c] = fixed_[i]
                    ? 0.0
                    : dt * (force_[c] + state.external_forces[c] -
                            (alpha_ * mass_[i] + damping_) * v[c] - (beta_ + dt) * stiffness_v_[c]);
  // A = P^T L D L^T P  ->  dv = P^T L^-T D^-1 L^-1 P rhs, without temporaries.
  // (P b)[P(i)] = b[i]: written as loops, Eigen's permutation products allocate here.
  const auto& forward = factor_.permutationP().indices();
  for (Eigen::Index i = 0; i < rhs_.size(); ++i) permuted_[forward[i]] = rhs_[i];
  factor_.matrixL().solveInPlace(permuted_);
  permuted_.array() *= inverse_d_.array();
  factor_.matrixU().solveInPlace(permuted_);
  const auto& backward = factor_.permutationPinv().indices();
  for (Eigen::Index i = 0; i < rhs_.size(); ++i) dv_[backward[i]] = permuted_[i];
  for (uint32_t i = 0; i < model.node_count(); ++i)
    for (uint32_t c = 3 * i; c < 3 * i + 3; ++c) {
      if (fixed_[i]) {
        v[c] = 0.0;
        continue;
      }
      v[c] += dv_[c];
      x[c] += dt * v[c];
    }
  return 0;  // the model checks divergence after the step
}

}  // namespace tacta::models
