// Shared helpers for the corotational_fem tests: a model built straight from the core library
// on a common test mesh, and the body state arrays the engine would own.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "corotational_fem.hpp"
#include "tacta/models/test_meshes.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::corotational::testing {

inline std::unique_ptr<CorotationalFem> make_model(const TestMesh& mesh,
                                                   const tacta_material& material,
                                                   const Options& options = {}) {
  return std::make_unique<CorotationalFem>(mesh.view(), material, mesh.masses, mesh.fixed, options);
}

// Positions, velocities and external forces of one body, as plain arrays.
struct BodyState {
  std::vector<double> positions, velocities, external_forces;
  tacta_body_state state{};
  explicit BodyState(const TestMesh& mesh)
      : positions(mesh.positions),
        velocities(mesh.positions.size(), 0.0),
        external_forces(mesh.positions.size(), 0.0) {
    state.node_count = mesh.node_count();
    state.positions = positions.data();
    state.velocities = velocities.data();
    state.external_forces = external_forces.data();
  }
  void add_gravity(const TestMesh& mesh, std::array<double, 3> g) {
    for (uint32_t i = 0; i < mesh.node_count(); ++i)
      for (int c = 0; c < 3; ++c) external_forces[3 * i + c] += mesh.masses[i] * g[c];
  }
  // A sideways kick: x velocity rate * z (m/s), growing toward a beam's tip along z.
  void kick_sideways(const TestMesh& mesh, double rate) {
    for (uint32_t i = 0; i < mesh.node_count(); ++i)
      velocities[3 * i] = rate * mesh.positions[3 * i + 2];
  }
  double kinetic_energy(const TestMesh& mesh) const {
    double sum = 0.0;
    for (size_t k = 0; k < velocities.size(); ++k)
      sum += 0.5 * mesh.masses[k / 3] * velocities[k] * velocities[k];
    return sum;
  }
};

}  // namespace tacta::models::corotational::testing
