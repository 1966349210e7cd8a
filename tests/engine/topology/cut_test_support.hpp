// Meshes, blades and measures shared by the cutting tests: a 4 x 2 x 2 box of unit cells, planar
// blades made of two triangles, volumes summed from the tets, pieces counted through shared nodes.
#pragma once

#include <array>
#include <cstddef>
#include <set>
#include <vector>

#include "mesh/geometry.hpp"
#include "tacta/mesh_build.hpp"
#include "topology/cut_mesh.hpp"

namespace tacta::test {

// [0, 4] x [0, 2] x [0, 2] m in unit cells: 16 cells, 96 tets, 45 nodes.
inline VolumeMesh box_4x2x2() { return make_box_grid({4, 2, 2}, {4, 2, 2}, {0, 0, 0}); }

// The quad a-b-c-d as two blade triangles (a, b, c) and (a, c, d), 9 doubles each.
inline std::vector<double> quad_blade(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  std::vector<double> out;
  for (const Vec3& p : {a, b, c, a, c, d}) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// The plane x = x0 + sy * y + sz * z over y, z in [y_lo, y_hi] x [z_lo, z_hi] (m).
inline std::vector<double> tilted_blade(double x0, double sy, double sz, double y_lo = -50,
                                        double y_hi = 50, double z_lo = -50, double z_hi = 50) {
  auto at = [&](double y, double z) { return Vec3{x0 + sy * y + sz * z, y, z}; };
  return quad_blade(at(y_lo, z_lo), at(y_hi, z_lo), at(y_hi, z_hi), at(y_lo, z_hi));
}

inline double tet_volume(const VolumeMesh& mesh, size_t t) {
  const uint32_t* n = &mesh.tets[4 * t];
  const Vec3 a = point_at(mesh.positions.data(), n[0]);
  return triple(sub(point_at(mesh.positions.data(), n[1]), a),
                sub(point_at(mesh.positions.data(), n[2]), a),
                sub(point_at(mesh.positions.data(), n[3]), a)) /
         6.0;
}

inline double volume(const VolumeMesh& mesh) {
  double v = 0;
  for (size_t t = 0; t < mesh.tet_count(); ++t) v += tet_volume(mesh, t);
  return v;
}

// Pieces of the mesh: tets joined through shared nodes.
inline size_t pieces(const VolumeMesh& mesh) {
  mesh_detail::NodeUnion u(mesh.node_count());
  u.join_elements(mesh.tets, 4);
  std::set<uint32_t> roots;
  for (uint32_t n : mesh.tets) roots.insert(u.root(n));
  return roots.size();
}

inline size_t marked(const std::vector<uint8_t>& flags) {
  size_t count = 0;
  for (uint8_t f : flags) count += f;
  return count;
}

}  // namespace tacta::test
