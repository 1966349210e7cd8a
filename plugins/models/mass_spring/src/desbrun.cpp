#include "desbrun.hpp"

#include <Eigen/Dense>
#include <stdexcept>
#include <vector>

#include "mass_spring_model.hpp"

namespace tacta::models {

DesbrunSolver::DesbrunSolver(const MassSpringModel& model, double dt) {
  const uint32_t n = model.node_count();
  const SpringSet& springs = model.springs();
  const std::vector<uint8_t>& fixed = model.fixed();
  std::vector<Eigen::Triplet<double>> lap, system;
  for (size_t s = 0; s < springs.size(); ++s) {
    const int a = static_cast<int>(springs.ends[2 * s]),
              b = static_cast<int>(springs.ends[2 * s + 1]);
    const double k = springs.stiffness[s];
    lap.insert(lap.end(), {{a, a, k}, {b, b, k}, {a, b, -k}, {b, a, -k}});
    // C = alpha M + beta K with K approximated by L_k, as the linear part itself.
    const double h2k = (dt * dt + dt * model.stiffness_damping()) * k;
    if (!fixed[static_cast<size_t>(a)]) system.emplace_back(a, a, h2k);
    if (!fixed[static_cast<size_t>(b)]) system.emplace_back(b, b, h2k);
    if (!fixed[static_cast<size_t>(a)] && !fixed[static_cast<size_t>(b)])
      system.insert(system.end(), {{a, b, -h2k}, {b, a, -h2k}});
  }
  for (uint32_t i = 0; i < n; ++i) {
    any_fixed_ = any_fixed_ || fixed[i];
    const double diagonal = fixed[i] ? 1.0 : model.masses()[i] + dt * model.damping_per_node(i);
    system.emplace_back(static_cast<int>(i), static_cast<int>(i), diagonal);
  }
  laplacian_.resize(n, n);
  laplacian_.setFromTriplets(lap.begin(), lap.end());
  Eigen::SparseMatrix<double> matrix(n, n);
  matrix.setFromTriplets(system.begin(), system.end());
  factor_.compute(matrix);
  if (factor_.info() != Eigen::Success)
    throw std::invalid_argument(
        "mass_spring: Desbrun matrix M + dt^2 L_k is not positive definite");
  inverse_d_ = factor_.vectorD().cwiseInverse();
  for (Eigen::VectorXd* v : {&column_, &permuted_, &velocity_column_, &laplacian_v_}) v->setZero(n);
  force_.setZero(3 * n);
  dv_.setZero(3 * n);
}

void DesbrunSolver::solve_in_place(Eigen::VectorXd& column) noexcept {
  // (P b)[P(i)] = b[i]: written as loops, Eigen's permutation products allocate here.
  const auto& forward = factor_.permutationP().indices();
  for (Eigen::Index i = 0; i < column.size(); ++i) permuted_[forward[i]] = column[i];
  factor_.matrixL().solveInPlace(permuted_);
  permuted_.array() *= inverse_d_.array();
  factor_.matrixU().solveInPlace(permuted_);
  const auto& backward = factor_.permutationPinv().indices();
  for (Eigen::Index i = 0; i < column.size(); ++i) column[backward[i]] = permuted_[i];
}

void DesbrunSolver::step(const MassSpringModel& model, tacta_body_state& state,
                         double dt) noexcept {
  const uint32_t n = model.node_count();
  const std::vector<uint8_t>& fixed = model.fixed();
  double* x = state.positions;
  double* v = state.velocities;
  model.internal_forces(x, force_.data());
  for (uint32_t c = 0; c < 3; ++c) {
    for (uint32_t i = 0; i < n; ++i) velocity_column_[i] = v[3 * i + c];
    laplacian_v_.noalias() = laplacian_ * velocity_column_;
    for (uint32_t i = 0; i < n; ++i) {
      const uint32_t k = 3 * i + c;
      column_[i] =
          fixed[i] ? 0.0
                   : dt * (force_[k] + state.external_forces[k] - model.damping_per_node(i) * v[k] -
                           (dt + model.stiffness_damping()) * laplacian_v_[i]);
    }
    solve_in_place(column_);
    for (uint32_t i = 0; i < n; ++i) dv_[3 * i + c] = column_[i];
  }
  if (!any_fixed_ && model.options().desbrun_correction) correct_angular_momentum(model, state, dt);
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t k = 3 * i; k < 3 * i + 3; ++k) {
      if (fixed[i]) {
        v[k] = 0.0;
        continue;
      }
      v[k] += dv_[k];
      x[k] += dt * v[k];
    }
}

void DesbrunSolver::correct_angular_momentum(const MassSpringModel& model,
                                             const tacta_body_state& state, double dt) noexcept {
  using Vec = Eigen::Vector3d;
  const uint32_t n = model.node_count();
  const double* x = state.positions;
  double total_mass = 0;
  Vec centre = Vec::Zero();
  for (uint32_t i = 0; i < n; ++i) {
    total_mass += model.masses()[i];
    centre += model.masses()[i] * Vec(x[3 * i], x[3 * i + 1], x[3 * i + 2]);
  }
  centre /= total_mass;
  // Angular momentum change the explicit forces would give (spring forces are central: no
  // torque) against the one the filtered dv gives; inertia tensor about the centre of mass.
  Vec expected = Vec::Zero(), actual = Vec::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  for (uint32_t i = 0; i < n; ++i) {
    const double m = model.masses()[i];
    const Vec r = Vec(x[3 * i], x[3 * i + 1], x[3 * i + 2]) - centre;
    const Vec v(state.velocities[3 * i], state.velocities[3 * i + 1], state.velocities[3 * i + 2]);
    const Vec f_other = Vec(state.external_forces[3 * i], state.external_forces[3 * i + 1],
                            state.external_forces[3 * i + 2]) -
                        model.damping_per_node(i) * v;
    expected += dt * r.cross(f_other);
    actual += m * r.cross(Vec(dv_[3 * i], dv_[3 * i + 1], dv_[3 * i + 2]));
    inertia += m * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
  }
  const Eigen::LDLT<Eigen::Matrix3d> inertia_ldlt(inertia);
  const Vec omega = inertia_ldlt.solve(actual - expected);  // 1/s
  if (!omega.allFinite()) return;
  for (uint32_t i = 0; i < n; ++i) {
    const Vec r = Vec(x[3 * i], x[3 * i + 1], x[3 * i + 2]) - centre;
    const Vec correction = omega.cross(r);
    for (uint32_t c = 0; c < 3; ++c) dv_[3 * i + c] -= correction[c];
  }
}

}  // namespace tacta::models
