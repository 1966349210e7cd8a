#include "fd_debunne_model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "tacta/models/edge_graph.hpp"

namespace tacta::models {

FdDebunneModel::FdDebunneModel(const tacta_model_setup& setup, const FdDebunneOptions& options)
    : options_(options) {
  const tacta_mesh_view& mesh = *setup.mesh;
  const tacta_material& material = *setup.material;
  if (mesh.node_count == 0 || mesh.edge_count == 0)
    throw std::invalid_argument("fd_debunne needs a mesh with nodes and edges");
  if (!(material.density > 0)) throw std::invalid_argument("fd_debunne: density must be > 0");
  if (!(material.lame_mu > 0) || !(material.lame_lambda + material.lame_mu > 0))
    throw std::invalid_argument("fd_debunne: needs mu > 0 and lambda + mu > 0");
  node_count_ = mesh.node_count;
  rest_.assign(mesh.rest_positions, mesh.rest_positions + 3 * static_cast<size_t>(node_count_));
  mass_.assign(setup.masses, setup.masses + node_count_);
  fixed_.assign(node_count_, 0);
  if (setup.fixed) fixed_.assign(setup.fixed, setup.fixed + node_count_);
  for (uint32_t i = 0; i < node_count_; ++i)
    if (!(mass_[i] > 0) && !fixed_[i])
      throw std::invalid_argument("fd_debunne: node " + std::to_string(i) + " has mass <= 0");
  mu_ = material.lame_mu;
  lambda_plus_mu_ = material.lame_lambda + material.lame_mu;
  scale_ = options.operator_scale == FdDebunneOptions::OperatorScale::kDimension
               ? static_cast<double>(mesh.dimension == 0 ? 3u : mesh.dimension)
               : 1.0;

  const EdgeGraph graph = EdgeGraph::from_mesh(mesh);
  offset_ = graph.offset;
  neighbour_ = graph.neighbour;
  weight_.assign(neighbour_.size(), 0.0);
  direction_.assign(3 * neighbour_.size(), 0.0);
  std::vector<double> length(neighbour_.size()), length_sum(node_count_, 0.0);
  for (uint32_t i = 0; i < node_count_; ++i)
    for (uint32_t k = offset_[i]; k < offset_[i + 1]; ++k) {
      const uint32_t j = neighbour_[k];
      double l2 = 0;
      for (int c = 0; c < 3; ++c) {
        const double delta = rest_[3 * i + c] - rest_[3 * j + c];
        direction_[3 * k + c] = delta;
        l2 += delta * delta;
      }
      length[k] = std::sqrt(l2);
      if (!(length[k] > 0))
        throw std::invalid_argument("fd_debunne: nodes " + std::to_string(i) + " and " +
                                    std::to_string(j) + " coincide at rest");
      for (int c = 0; c < 3; ++c) direction_[3 * k + c] /= length[k];
      length_sum[i] += length[k];
    }
  // Per-entry weight: lumped volume V_i = m_i / rho times the operator coefficient 2/(S_i L_ij).
  for (uint32_t i = 0; i < node_count_; ++i)
    for (uint32_t k = offset_[i]; k < offset_[i + 1]; ++k)
      weight_[k] = scale_ * 2.0 * (mass_[i] / material.density) / (length_sum[i] * length[k]);
  if (options.symmetric) {
    std::vector<double> symmetric(weight_.size());
    for (uint32_t i = 0; i < node_count_; ++i)
      for (uint32_t k = offset_[i]; k < offset_[i + 1]; ++k) {
        const uint32_t j = neighbour_[k];
        double back = 0;
        for (uint32_t q = offset_[j]; q < offset_[j + 1]; ++q)
          if (neighbour_[q] == i) back = weight_[q];
        symmetric[k] = 0.5 * (weight_[k] + back);
      }
    weight_ = symmetric;
  }
  force_.assign(3 * static_cast<size_t>(node_count_), 0.0);
  guard_ = DivergenceGuard(mesh, options.divergence_stretch);
}

void FdDebunneModel::internal_forces(const double* positions, double* forces) const noexcept {
  for (uint32_t i = 0; i < node_count_; ++i) {
    double f[3] = {0, 0, 0};
    const double* xi = positions + 3 * static_cast<size_t>(i);
    const double* ri = rest_.data() + 3 * static_cast<size_t>(i);
    for (uint32_t k = offset_[i]; k < offset_[i + 1]; ++k) {
      const size_t j3 = 3 * static_cast<size_t>(neighbour_[k]);
      const double* u = direction_.data() + 3 * static_cast<size_t>(k);
      double dd[3];  // d_j - d_i, m
      for (int c = 0; c < 3; ++c) dd[c] = (positions[j3 + c] - rest_[j3 + c]) - (xi[c] - ri[c]);
      const double along = dd[0] * u[0] + dd[1] * u[1] + dd[2] * u[2];
      for (int c = 0; c < 3; ++c)
        f[c] += weight_[k] * (mu_ * dd[c] + lambda_plus_mu_ * along * u[c]);
    }
    for (int c = 0; c < 3; ++c) forces[3 * i + c] = f[c];
  }
}

double FdDebunneModel::elastic_energy(const double* positions) noexcept {
  internal_forces(positions, force_.data());
  double energy = 0;
  for (size_t k = 0; k < force_.size(); ++k) energy -= 0.5 * (positions[k] - rest_[k]) * force_[k];
  return energy;
}

uint32_t FdDebunneModel::step(tacta_body_state& state, double dt) noexcept {
  internal_forces(state.positions, force_.data());
  double* x = state.positions;
  double* v = state.velocities;
  const bool symplectic = options_.integrator == FdDebunneOptions::Integrator::kSymplecticEuler;
  for (uint32_t i = 0; i < node_count_; ++i) {
    const size_t b = 3 * static_cast<size_t>(i);
    if (fixed_[i]) {
      v[b] = v[b + 1] = v[b + 2] = 0.0;
      continue;
    }
    for (size_t c = b; c < b + 3; ++c) {
      const double acceleration =
          (force_[c] + state.external_forces[c] - options_.damping * v[c]) / mass_[i];
      if (symplectic) {
        v[c] += dt * acceleration;
        x[c] += dt * v[c];
      } else {  // the paper's forward Euler: position from the old velocity
        x[c] += dt * v[c];
        v[c] += dt * acceleration;
      }
    }
  }
  return guard_.check(x, v);
}

}  // namespace tacta::models
