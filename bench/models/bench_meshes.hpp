// Meshes for the model benchmarks: clamped boxes of about 500 to 50k tets, and SOFA's beams
// scene (four 5x5x20-node beams, 7,296 tets, 2,000 nodes; numbers in docs/REFERENCES.md).
#pragma once

#include <array>
#include <cstdint>

#include "tacta/models/test_meshes.hpp"

namespace tacta::bench {

// A box of cells x cells x (cells + extra) cubes of 1 cm (6 tets each), clamped at z = 0. Tet counts: 4 -> 480, 7 -> 2,058, 12 -> 10,368, 20 -> 50,400.
inline models::TestMesh clamped_box(uint32_t cells, uint32_t extra) {
  const double edge = 0.01;  // m per cube
  models::TestMesh mesh = models::box_tet_mesh(
      {cells, cells, cells + extra}, {edge * cells, edge * cells, edge * (cells + extra)}, 1000.0);
  mesh.fix_plane(2, 0.0);
  return mesh;
}

// SOFA's TetrahedronFEMForceField.scn: four beams from (-5,-5,0) to (5,5,40), 5x5x20 nodes
// each, side by side along x (they never touch: there is no collision in that scene); density
// 0.2, nodes with z <= 0.1 fixed.
inline models::TestMesh sofa_beams() {
  models::TestMesh all;
  for (int beam = 0; beam < 4; ++beam) {
    const models::TestMesh one = models::box_tet_mesh({4, 4, 19}, {10.0, 10.0, 40.0}, 0.2);
    const uint32_t base = all.node_count();
    for (uint32_t i = 0; i < one.node_count(); ++i) {
      all.positions.push_back(one.positions[3 * i] - 5.0 + 20.0 * beam);
      all.positions.push_back(one.positions[3 * i + 1] - 5.0);
      all.positions.push_back(one.positions[3 * i + 2]);
    }
    for (uint32_t t : one.tets) all.tets.push_back(base + t);
    for (uint32_t e : one.edges) all.edges.push_back(base + e);
    for (uint32_t t : one.triangles) all.triangles.push_back(base + t);
    all.masses.insert(all.masses.end(), one.masses.begin(), one.masses.end());
  }
  all.fixed.assign(all.node_count(), 0);
  for (uint32_t i = 0; i < all.node_count(); ++i) all.fixed[i] = all.positions[3 * i + 2] <= 0.1;
  return all;
}

}  // namespace tacta::bench
