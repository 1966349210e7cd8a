#include "mass_spring_model.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "baraff_witkin.hpp"
#include "desbrun.hpp"
#include "tacta/models/spring_stiffness.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models {

void SpringSet::forces(const double* x, uint32_t node_count, double* out) const noexcept {
  for (size_t k = 0; k < 3 * static_cast<size_t>(node_count); ++k) out[k] = 0.0;
  for (size_t s = 0; s < size(); ++s) {
    const size_t a = 3 * static_cast<size_t>(ends[2 * s]),
                 b = 3 * static_cast<size_t>(ends[2 * s + 1]);
    const double dx = x[b] - x[a], dy = x[b + 1] - x[a + 1], dz = x[b + 2] - x[a + 2];
    const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
    if (!(length > 0)) continue;  // coincident ends: no direction, no force
    const double scale = stiffness[s] * (length - rest_length[s]) / length;  // N/m
    out[a] += scale * dx, out[a + 1] += scale * dy, out[a + 2] += scale * dz;
    out[b] -= scale * dx, out[b + 1] -= scale * dy, out[b + 2] -= scale * dz;
  }
}

double SpringSet::energy(const double* x) const noexcept {
  double energy = 0;
  for (size_t s = 0; s < size(); ++s) {
    const size_t a = 3 * static_cast<size_t>(ends[2 * s]),
                 b = 3 * static_cast<size_t>(ends[2 * s + 1]);
    const double dx = x[b] - x[a], dy = x[b + 1] - x[a + 1], dz = x[b + 2] - x[a + 2];
    const double stretch = std::sqrt(dx * dx + dy * dy + dz * dz) - rest_length[s];
    energy += 0.5 * stiffness[s] * stretch * stretch;
  }
  return energy;
}

MassSpringModel::MassSpringModel(const tacta_model_setup& setup, const MassSpringOptions& options)
    : options_(options) {
  const tacta_mesh_view& mesh = *setup.mesh;
  if (mesh.tet_count == 0)
    throw std::invalid_argument(
        "mass_spring needs a tetrahedral mesh (stiffness from tet volumes)");
  node_count_ = mesh.node_count;
  alpha_ = setup.material->rayleigh_mass;
  beta_ = setup.material->rayleigh_stiffness;
  mass_.assign(setup.masses, setup.masses + node_count_);
  fixed_.assign(node_count_, 0);
  if (setup.fixed) fixed_.assign(setup.fixed, setup.fixed + node_count_);
  for (uint32_t i = 0; i < node_count_; ++i)
    if (!(mass_[i] > 0) && !fixed_[i])
      throw std::invalid_argument("mass_spring: node " + std::to_string(i) + " has mass <= 0");
  const std::vector<double> stiffness =
      edge_stiffness("mass_spring", mesh, *setup.material, options.stiffness_rule);
  for (uint32_t e = 0; e < mesh.edge_count; ++e) {
    const uint32_t a = mesh.edges[2 * e], b = mesh.edges[2 * e + 1];
    springs_.ends.insert(springs_.ends.end(), {a, b});
    springs_.rest_length.push_back(
        (node_position(mesh.rest_positions, a) - node_position(mesh.rest_positions, b)).norm());
    springs_.stiffness.push_back(stiffness[e]);
  }
  force_.assign(3 * static_cast<size_t>(node_count_), 0.0);
  guard_ = DivergenceGuard(mesh, options.divergence_stretch);
  if (options.integrator == MassSpringOptions::Integrator::kImplicitEuler)
    baraff_witkin_ = std::make_unique<BaraffWitkinSolver>(*this);
  if (options.integrator == MassSpringOptions::Integrator::kDesbrun) {
    if (!(setup.dt > 0)) throw std::invalid_argument("mass_spring: desbrun needs dt > 0 at create");
    desbrun_ = std::make_unique<DesbrunSolver>(*this, setup.dt);
  }
}

MassSpringModel::~MassSpringModel() = default;

int MassSpringModel::last_cg_iterations() const {
  return baraff_witkin_ ? baraff_witkin_->last_iterations() : 0;
}

uint32_t MassSpringModel::step(tacta_body_state& state, double dt) noexcept {
  uint32_t status = 0;
  if (baraff_witkin_)
    status = baraff_witkin_->step(*this, state, dt);
  else if (desbrun_)
    desbrun_->step(*this, state, dt);
  else
    step_symplectic(state, dt);
  return status | guard_.check(state.positions, state.velocities);
}

uint32_t MassSpringModel::step_symplectic(tacta_body_state& state, double dt) noexcept {
  springs_.forces(state.positions, node_count_, force_.data());
  for (uint32_t i = 0; i < node_count_; ++i) {
    const size_t b = 3 * static_cast<size_t>(i);
    for (size_t c = b; c < b + 3; ++c) {
      if (fixed_[i]) {
        state.velocities[c] = 0.0;
        continue;
      }
      const double f =
          force_[c] + state.external_forces[c] - damping_per_node(i) * state.velocities[c];
      state.velocities[c] += dt * f / mass_[i];
      state.positions[c] += dt * state.velocities[c];
    }
  }
  return 0;
}

}  // namespace tacta::models
