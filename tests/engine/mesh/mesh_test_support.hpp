// Paths and measures shared by the mesh tests.
#pragma once

#include <cmath>
#include <numeric>
#include <string>

#include "tacta/mesh_io.hpp"

namespace tacta::test {

inline std::string asset_mesh(const std::string& name) {
  return std::string(TACTA_SOURCE_DIR) + "/assets/meshes/" + name;
}
inline std::string test_mesh(const std::string& name) {
  return std::string(TACTA_SOURCE_DIR) + "/tests/data/meshes/" + name;
}

// Sum of the element volumes (m^3), through the lumped masses at unit density.
inline double total_volume(const VolumeMesh& mesh) {
  std::vector<double> m = lumped_masses(mesh, 1.0);
  return std::accumulate(m.begin(), m.end(), 0.0);
}

inline SurfaceMesh boundary_of(const VolumeMesh& mesh) {
  SurfaceMesh s;
  s.positions = mesh.positions;
  s.triangles = mesh.triangles;
  return s;
}

}  // namespace tacta::test
