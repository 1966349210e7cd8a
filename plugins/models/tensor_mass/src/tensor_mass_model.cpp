#include "tensor_mass_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "tacta/models/edge_graph.hpp"
#include "tacta/models/tet_geometry.hpp"
#include "tensor_mass_implicit.hpp"

namespace tacta::models {

TensorMassModel::TensorMassModel(const tacta_model_setup& setup, const TensorMassOptions& options)
    : options_(options) {
  const tacta_mesh_view& mesh = *setup.mesh;
  const tacta_material& material = *setup.material;
  if (mesh.tet_count == 0) throw std::invalid_argument("tensor_mass needs a tetrahedral mesh");
  node_count_ = mesh.node_count;
  rest_.assign(mesh.rest_positions, mesh.rest_positions + 3 * static_cast<size_t>(node_count_));
  mass_.assign(setup.masses, setup.masses + node_count_);
  fixed_.assign(node_count_, 0);
  if (setup.fixed) fixed_.assign(setup.fixed, setup.fixed + node_count_);
  gamma_.resize(node_count_);
  for (uint32_t i = 0; i < node_count_; ++i) {
    if (!(mass_[i] > 0) && !fixed_[i])
      throw std::invalid_argument("tensor_mass: node " + std::to_string(i) + " has mass <= 0");
    gamma_[i] = material.rayleigh_mass * mass_[i] + options.damping;
  }
  edges_.assign(mesh.edges, mesh.edges + 2 * static_cast<size_t>(mesh.edge_count));
  const EdgeGraph graph = EdgeGraph::from_mesh(mesh);
  vertex_block_.assign(node_count_, Eigen::Matrix3d::Zero());
  edge_block_.assign(mesh.edge_count, Eigen::Matrix3d::Zero());
  const double lambda = material.lame_lambda, mu = material.lame_mu;
  for (uint32_t t = 0; t < mesh.tet_count; ++t) {
    const uint32_t* tet = mesh.tets + 4 * static_cast<size_t>(t);
    for (int k = 0; k < 4; ++k)
      if (tet[k] >= node_count_)
        throw std::invalid_argument("tensor_mass: tet " + std::to_string(t) + " names node " +
                                    std::to_string(tet[k]) + " of " + std::to_string(node_count_));
    const Vec3 x0 = node_position(rest_.data(), tet[0]), x1 = node_position(rest_.data(), tet[1]),
               x2 = node_position(rest_.data(), tet[2]), x3 = node_position(rest_.data(), tet[3]);
    const double volume = tet_signed_volume(x0, x1, x2, x3);
    if (!(volume > 0))
      throw std::invalid_argument("tensor_mass: tet " + std::to_string(t) +
                                  " has non-positive volume (expected det(x1-x0,x2-x0,x3-x0) > 0)");
    const auto g = tet_shape_gradients(x0, x1, x2, x3);
    for (size_t p = 0; p < 4; ++p)
      for (size_t q = 0; q < 4; ++q) {
        const Eigen::Matrix3d block =
            volume * (lambda * g[p] * g[q].transpose() + mu * g[q] * g[p].transpose() +
                      mu * g[p].dot(g[q]) * Eigen::Matrix3d::Identity());
        const uint32_t a = tet[p], b = tet[q];
        if (a == b) {
          vertex_block_[a] += block;
          continue;
        }
        const uint32_t e = graph.find_edge(a, b);
        if (e == UINT32_MAX)
          throw std::invalid_argument("tensor_mass: edge (" + std::to_string(a) + ", " +
                                      std::to_string(b) + ") of tet " + std::to_string(t) +
                                      " is missing from mesh.edges");
        if (edges_[2 * e] == a) edge_block_[e] += block;  // store K_ab once per ordered edge
      }
  }
  previous_.assign(rest_.size(), 0.0);
  scratch_.assign(rest_.size(), 0.0);
  force_.assign(rest_.size(), 0.0);
  guard_ = DivergenceGuard(mesh, options.divergence_stretch);
  bool implicit = options.integrator == TensorMassOptions::Integrator::kImplicitEuler;
  if (options.integrator == TensorMassOptions::Integrator::kAuto) {
    // Central differences past 0.9 of their limit grow without bound (the liver at 1 ms froze at
    // once): implicit Euler, unconditionally stable, takes over and the report says so.
    const double limit = central_difference_limit();
    implicit = setup.dt > 0 && limit > 0 && setup.dt > 0.9 * limit;
    char text[256];
    std::snprintf(text, sizeof text,
                  "integrator auto: %s (central differences are stable below %.3g s; dt is %.3g s)",
                  implicit ? "implicit_euler" : "central_difference", limit, setup.dt);
    note_ = text;
  }
  if (implicit) {
    if (!(setup.dt > 0)) throw std::invalid_argument("tensor_mass: implicit_euler needs dt > 0");
    implicit_ = std::make_unique<ImplicitEulerSolver>(*this, mass_, fixed_, material,
                                                      options.damping, setup.dt);
  }
}

TensorMassModel::~TensorMassModel() = default;

double TensorMassModel::central_difference_limit() const {
  std::vector<double> row_sum(3 * static_cast<size_t>(node_count_),
                              0.0);  // sum of |K| along each row
  const auto add_rows = [&](uint32_t node, const Eigen::Matrix3d& block) {
    for (int r = 0; r < 3; ++r)
      row_sum[3 * static_cast<size_t>(node) + static_cast<size_t>(r)] +=
          block.row(r).cwiseAbs().sum();
  };
  for (uint32_t i = 0; i < node_count_; ++i) add_rows(i, vertex_block_[i]);
  for (size_t e = 0; e < edge_block_.size(); ++e) {
    add_rows(edges_[2 * e], edge_block_[e]);
    add_rows(edges_[2 * e + 1], edge_block_[e].transpose());
  }
  double omega_squared = 0;
  for (uint32_t i = 0; i < node_count_; ++i)
    if (!fixed_[i] && mass_[i] > 0)
      for (size_t r = 0; r < 3; ++r)
        omega_squared = std::max(omega_squared, row_sum[3 * size_t{i} + r] / mass_[i]);
  return omega_squared > 0 ? 2.0 / std::sqrt(omega_squared) : 0.0;
}

void TensorMassModel::apply_stiffness(const double* u, double* y) const noexcept {
  using Map = Eigen::Map<Eigen::Vector3d>;
  using ConstMap = Eigen::Map<const Eigen::Vector3d>;
  for (uint32_t i = 0; i < node_count_; ++i)
    Map(y + 3 * i) = vertex_block_[i] * ConstMap(u + 3 * i);
  for (size_t e = 0; e < edge_block_.size(); ++e) {
    const size_t a = 3 * static_cast<size_t>(edges_[2 * e]),
                 b = 3 * static_cast<size_t>(edges_[2 * e + 1]);
    Map(y + a) += edge_block_[e] * ConstMap(u + b);
    Map(y + b) += edge_block_[e].transpose() * ConstMap(u + a);
  }
}

void TensorMassModel::internal_forces(const double* positions, double* forces) const noexcept {
  double* d = scratch_.data();  // fully rewritten on each call
  for (size_t k = 0; k < rest_.size(); ++k) d[k] = positions[k] - rest_[k];
  apply_stiffness(d, forces);
  for (size_t k = 0; k < rest_.size(); ++k) forces[k] = -forces[k];
}

double TensorMassModel::elastic_energy(const double* positions) noexcept {
  internal_forces(positions, force_.data());
  double energy = 0;
  for (size_t k = 0; k < rest_.size(); ++k) energy -= 0.5 * (positions[k] - rest_[k]) * force_[k];
  return energy;
}

void TensorMassModel::begin(const tacta_body_state& state, double dt) noexcept {
  // Central differences need x(t - dt); a first-order estimate from the current velocity.
  for (size_t k = 0; k < rest_.size(); ++k)
    previous_[k] = state.positions[k] - dt * state.velocities[k];
  has_history_ = true;
}

uint32_t TensorMassModel::step(tacta_body_state& state, double dt) noexcept {
  if (!implicit_) return step_central(state, dt);
  implicit_->step(*this, state, dt);
  return guard_.check(state.positions, state.velocities);
}

uint32_t TensorMassModel::step_central(tacta_body_state& state, double dt) noexcept {
  if (!has_history_) begin(state, dt);
  double* x = state.positions;
  double* v = state.velocities;
  internal_forces(x, force_.data());
  const double inv_dt2 = 1.0 / (dt * dt);
  for (uint32_t i = 0; i < node_count_; ++i) {
    const size_t b = 3 * static_cast<size_t>(i);
    if (fixed_[i]) {
      for (size_t c = b; c < b + 3; ++c) {
        v[c] = 0.0;
        previous_[c] = x[c];
      }
      continue;
    }
    const double half_gamma = gamma_[i] / (2.0 * dt);
    const double lhs = mass_[i] * inv_dt2 + half_gamma;
    for (size_t c = b; c < b + 3; ++c) {
      const double next = (force_[c] + state.external_forces[c] + 2.0 * mass_[i] * inv_dt2 * x[c] -
                           (mass_[i] * inv_dt2 - half_gamma) * previous_[c]) /
                          lhs;
      previous_[c] = x[c];
      v[c] = (next - x[c]) / dt;  // the velocity at t + dt/2, consistent with begin()
      x[c] = next;
    }
  }
  return guard_.check(x, v);
}

}  // namespace tacta::models
