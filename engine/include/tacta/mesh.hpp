// Meshes as the engine holds them: flat arrays of doubles and indices, so that they cross the
// plugin boundary as spans without copies. Units: metres.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace tacta {

// A triangle surface (render and collision surface, or an imported OBJ/STL/PLY/glTF).
struct SurfaceMesh {
  std::vector<double> positions;    // 3 per vertex, m
  std::vector<uint32_t> triangles;  // 3 per triangle, counter-clockwise seen from outside
  // Texture coordinates per triangle corner (u, v for each of its 3 corners: 6 per triangle),
  // so a seam keeps both sides' values on a welded vertex; empty when the file has none.
  std::vector<double> corner_uvs;
  std::string source;  // file it came from, for messages
  size_t vertex_count() const { return positions.size() / 3; }
  size_t triangle_count() const { return triangles.size() / 3; }
};

// Surface vertices bound to volume elements by barycentric weights (voxelised bodies, or a fine
// render surface over a coarse simulation mesh).
struct Embedding {
  SurfaceMesh surface;
  std::vector<uint32_t> element;  // 1 per surface vertex: index of the tet that holds it
  std::vector<double> weights;    // 4 per surface vertex: barycentric weights in that tet
};

// A simulation mesh: the nodes a model moves, its elements and its boundary.
struct VolumeMesh {
  std::vector<double> positions;  // 3 per node, m (rest state)
  std::vector<uint32_t> tets;     // 4 per tet, positively oriented
  std::vector<uint32_t> quads;    // 4 per quad, planar meshes (the paper's unit square)
  std::vector<uint32_t>
      triangles;  // 3 per triangle: boundary surface, outward (or the planar elements)
  std::vector<uint32_t> edges;  // 2 per unique undirected edge (i < j) of all elements
  uint32_t dimension = 3;       // 3 volume, 2 planar (unit thickness)
  std::optional<Embedding> embedding;
  std::string source;  // file or primitive it came from
  size_t node_count() const { return positions.size() / 3; }
  size_t tet_count() const { return tets.size() / 4; }
};

// Element quality summary, for `tacta mesh-info` and load-time checks.
struct MeshQuality {
  double min_volume = 0;  // m^3 (tets) or m^2 (planar)
  double max_volume = 0;
  double min_edge = 0;  // m
  double max_edge = 0;
  double worst_aspect_ratio = 0;  // longest edge / shortest altitude-ish measure, 1 is best
  double min_dihedral_deg =
      0;  // tets: smallest dihedral angle, degrees (70.5 regular; slivers near 0)
  double max_dihedral_deg = 0;   // tets: largest dihedral angle, degrees (near 180: a flat tet)
  double min_radius_ratio = 0;   // tets: smallest 3 r_in / r_circ (1 regular, 0 flat)
  double mean_radius_ratio = 0;  // tets: mean of 3 r_in / r_circ
  double bounds_min[3] = {0, 0, 0};
  double bounds_max[3] = {0, 0, 0};
};

}  // namespace tacta
