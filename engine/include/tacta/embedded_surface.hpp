// A fine surface carried by a coarser tetrahedral mesh: every surface vertex follows the four nodes
// of one tet by fixed barycentric weights. It is what a body looks like, what the haptic proxy
// slides on and what collides, while the tets are what the model moves. Forces on the surface go
// back to the nodes by the transpose of the same weights, so the work a force does on the surface
// equals the work its node forces do (energy-consistent) and total force and moment are kept.
// Units: metres, newtons. Updating it each tick allocates nothing.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tacta/mesh.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

struct EmbeddedSurface {
  std::vector<uint32_t> triangles;     // 3 per triangle, counter-clockwise seen from outside
  std::vector<double> corner_uvs;      // 6 per triangle (u, v per corner), or empty: for texturing
  std::vector<double> rest_positions;  // 3 per vertex, m (as given, after scale and translate)
  std::vector<uint32_t> tet;           // 1 per vertex: the tet it follows
  std::vector<uint32_t> nodes;         // 4 per vertex: that tet's nodes
  std::vector<double> weights;  // 4 per vertex: barycentric in that tet (sum 1; some < 0 outside)
  // 3 per vertex, m: deformed, as of the last update_embedded_surface; while a run's haptic
  // proxy keeps it (collision.proxy_refit: sliced) only the vertices near its queries are current
  // between frames: interpolate from the nodes (interpolate_to_surface) for the whole surface.
  std::vector<double> positions;
  std::vector<double>
      normals;  // 3 per vertex: unit, area-weighted, at the last update_embedded_surface
  // 1 per triangle: 1 when a cut made it (drawn in the cut colour); empty while never cut
  std::vector<uint8_t> cut_triangles;
  size_t extrapolated_vertices = 0;  // vertices outside every tet, bound to the nearest one
  std::string source;                // file it came from, for messages
  size_t vertex_count() const { return rest_positions.size() / 3; }
  size_t triangle_count() const { return triangles.size() / 3; }
};

// Binds each vertex of `surface` to the tet of `mesh` that holds it (the one whose smallest
// barycentric weight is largest); a vertex outside every tet gets the tet that needs the least
// extrapolation (weights below 0), counted in a warning. Load time; nearby tets found through a grid.
Embedding bind_surface_to_tets(const SurfaceMesh& surface, const VolumeMesh& mesh,
                               LoadReport* report = nullptr);

// The runtime surface of a mesh that carries an Embedding (voxelised or given `surface:`), at
// rest: positions and normals filled. Throws InputError when the embedding does not fit the mesh.
EmbeddedSurface make_embedded_surface(const VolumeMesh& mesh);

// Vertex v's value interpolated from node values (3 per node) into out[0..2].
inline void interpolate_vertex(const EmbeddedSurface& s, size_t v, const double* node_values,
                               double* out) noexcept {
  const uint32_t* n = &s.nodes[4 * v];
  const double* w = &s.weights[4 * v];
  for (size_t a = 0; a < 3; ++a)
    out[a] = w[0] * node_values[3 * n[0] + a] + w[1] * node_values[3 * n[1] + a] +
             w[2] * node_values[3 * n[2] + a] + w[3] * node_values[3 * n[3] + a];
}

// Surface values interpolated from node values (3 per node, e.g. positions or velocities) into
// `out` (3 per surface vertex). No allocation.
void interpolate_to_surface(const EmbeddedSurface& s, const double* node_values,
                            double* out) noexcept;

// Deformed positions and normals from node positions (3 per node, m). No allocation.
void update_embedded_surface(EmbeddedSurface& s, const double* node_positions) noexcept;

// Adds a force (N) acting at surface vertex v to the node forces (3 per node): the transpose of
// the interpolation, f_node += w f.
void spread_to_nodes(const EmbeddedSurface& s, uint32_t vertex, const double* force,
                     double* node_forces) noexcept;

// A point of surface triangle t at barycentric weights b (normalised), from node positions, m.
std::array<double, 3> surface_point(const EmbeddedSurface& s, uint32_t triangle, const double* b,
                                    const double* node_positions) noexcept;

}  // namespace tacta
