#include "baraff_witkin.hpp"

#include <cmath>

#include "mass_spring_model.hpp"
#include "tacta/vec3.hpp"

namespace tacta::models {

BaraffWitkinSolver::BaraffWitkinSolver(const MassSpringModel& model) {
  const uint32_t n = model.node_count();
  const SpringSet& springs = model.springs();
  std::vector<Eigen::Triplet<double>> pattern;
  auto block = [&](uint32_t a, uint32_t b) {
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) pattern.emplace_back(3 * a + r, 3 * b + c, 1.0);
  };
  for (uint32_t i = 0; i < n; ++i) block(i, i);
  for (size_t s = 0; s < springs.size(); ++s) {
    block(springs.ends[2 * s], springs.ends[2 * s + 1]);
    block(springs.ends[2 * s + 1], springs.ends[2 * s]);
  }
  matrix_.resize(3 * n, 3 * n);
  matrix_.setFromTriplets(pattern.begin(), pattern.end());
  matrix_.makeCompressed();
  auto slot = [&](uint32_t row, uint32_t col) {
    return static_cast<int32_t>(&matrix_.coeffRef(row, col) - matrix_.valuePtr());
  };
  auto block_slots = [&](uint32_t a, uint32_t b, std::vector<int32_t>& out) {
    for (uint32_t r = 0; r < 3; ++r)
      for (uint32_t c = 0; c < 3; ++c) out.push_back(slot(3 * a + r, 3 * b + c));
  };
  for (uint32_t i = 0; i < n; ++i) block_slots(i, i, node_slots_);
  for (size_t s = 0; s < springs.size(); ++s) {
    const uint32_t a = springs.ends[2 * s], b = springs.ends[2 * s + 1];
    block_slots(a, a, spring_slots_);
    block_slots(a, b, spring_slots_);
    block_slots(b, a, spring_slots_);
    block_slots(b, b, spring_slots_);
  }
  jacobian_.assign(9 * springs.size(), 0.0);
  for (Eigen::VectorXd* v : {&rhs_, &dv_, &residual_, &preconditioned_, &direction_, &product_,
                             &inverse_diagonal_, &force_})
    v->setZero(3 * n);
}

void BaraffWitkinSolver::assemble(const MassSpringModel& model, const double* x,
                                  double dt) noexcept {
  double* values = matrix_.valuePtr();
  for (Eigen::Index k = 0; k < matrix_.nonZeros(); ++k) values[k] = 0.0;
  const SpringSet& springs = model.springs();
  const std::vector<uint8_t>& fixed = model.fixed();
  for (uint32_t i = 0; i < model.node_count(); ++i) {
    const double diagonal = fixed[i] ? 1.0 : model.masses()[i] + dt * model.damping_per_node(i);
    for (int c = 0; c < 3; ++c) values[node_slots_[9 * i + 4 * c]] = diagonal;
  }
  for (size_t s = 0; s < springs.size(); ++s) {
    const uint32_t a = springs.ends[2 * s], b = springs.ends[2 * s + 1];
    double n[3] = {x[3 * b] - x[3 * a], x[3 * b + 1] - x[3 * a + 1], x[3 * b + 2] - x[3 * a + 2]};
    const double length = norm(n);
    double* jac = &jacobian_[9 * s];  // K_s = -df_a/dx_a, N/m (positive semi-definite)
    if (!(length > 0)) {
      for (int k = 0; k < 9; ++k) jac[k] = 0.0;
      continue;
    }
    for (double& c : n) c /= length;
    const double k = springs.stiffness[s];
    const double transverse = std::fmax(0.0, 1.0 - springs.rest_length[s] / length);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c)
        jac[3 * r + c] = k * (n[r] * n[c] + transverse * ((r == c ? 1.0 : 0.0) - n[r] * n[c]));
    const int32_t* slots = &spring_slots_[36 * s];
    // Implicit Euler with C = alpha M + beta K: the stiffness enters as (dt^2 + dt beta) K.
    const double h2 = dt * dt + dt * model.stiffness_damping();
    for (int q = 0; q < 9; ++q) {
      if (!fixed[a]) values[slots[q]] += h2 * jac[q];
      if (!fixed[a] && !fixed[b]) {
        values[slots[9 + q]] -= h2 * jac[q];
        values[slots[18 + q]] -= h2 * jac[q];
      }
      if (!fixed[b]) values[slots[27 + q]] += h2 * jac[q];
    }
  }
}

bool BaraffWitkinSolver::solve(int max_iterations, double tolerance) noexcept {
  for (Eigen::Index k = 0; k < matrix_.outerSize(); ++k)
    inverse_diagonal_[k] = 1.0 / matrix_.coeff(k, k);
  dv_.setZero();
  residual_ = rhs_;
  preconditioned_ = inverse_diagonal_.cwiseProduct(residual_);
  direction_ = preconditioned_;
  double rz = residual_.dot(preconditioned_);
  const double threshold = tolerance * tolerance * std::fmax(rhs_.squaredNorm(), 1e-300);
  last_iterations_ = 0;
  if (residual_.squaredNorm() <= threshold) return true;
  for (int it = 0; it < max_iterations; ++it) {
    product_.noalias() = matrix_ * direction_;
    const double step = rz / direction_.dot(product_);
    dv_ += step * direction_;
    residual_ -= step * product_;
    last_iterations_ = it + 1;
    if (residual_.squaredNorm() <= threshold) return true;
    preconditioned_ = inverse_diagonal_.cwiseProduct(residual_);
    const double rz_next = residual_.dot(preconditioned_);
    direction_ = preconditioned_ + (rz_next / rz) * direction_;
    rz = rz_next;
  }
  return false;
}

uint32_t BaraffWitkinSolver::step(const MassSpringModel& model, tacta_body_state& state,
                                  double dt) noexcept {
  double* x = state.positions;
  double* v = state.velocities;
  assemble(model, x, dt);
  model.internal_forces(x, force_.data());
  const SpringSet& springs = model.springs();
  const std::vector<uint8_t>& fixed = model.fixed();
  // rhs = dt (f0 + f_ext - C v + dt df/dx v) with C = alpha M + beta K: the K v part is
  // -(dt + beta) K v; df/dx v = -K v gathered spring by spring.
  const double kv_scale = dt + model.stiffness_damping();  // s
  for (uint32_t i = 0; i < model.node_count(); ++i)
    for (uint32_t c = 3 * i; c < 3 * i + 3; ++c)
      rhs_[c] = force_[c] + state.external_forces[c] - model.damping_per_node(i) * v[c];
  for (size_t s = 0; s < springs.size(); ++s) {
    const uint32_t a = springs.ends[2 * s], b = springs.ends[2 * s + 1];
    const double* jac = &jacobian_[9 * s];
    for (int r = 0; r < 3; ++r) {
      double jv = 0;  // K_s (v_b - v_a): the spring's df_a/dx v
      for (int c = 0; c < 3; ++c) jv += jac[3 * r + c] * (v[3 * b + c] - v[3 * a + c]);
      rhs_[3 * a + r] += kv_scale * jv;
      rhs_[3 * b + r] -= kv_scale * jv;
    }
  }
  for (uint32_t i = 0; i < model.node_count(); ++i)
    for (uint32_t c = 3 * i; c < 3 * i + 3; ++c) rhs_[c] = fixed[i] ? 0.0 : dt * rhs_[c];
  const bool converged = solve(model.options().cg_max_iterations, model.options().cg_tolerance);
  for (uint32_t i = 0; i < model.node_count(); ++i)
    for (uint32_t c = 3 * i; c < 3 * i + 3; ++c) {
      if (fixed[i]) {
        v[c] = 0.0;
        continue;
      }
      v[c] += dv_[c];
      x[c] += dt * v[c];
    }
  return converged ? 0u : TACTA_STEP_SOLVER_NOT_CONVERGED;
}

}  // namespace tacta::models
