// The faces of a tet mesh, and the data finalize derives from them (outward boundary triangles,
// unique edges): one copy for finalize, the cutting code (topology/) and its checks.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tacta/mesh.hpp"

namespace tacta::mesh_detail {

// Local node indices of the faces of a positive tet (a, b, c, d), each wound outward (counter-
// clockwise seen from outside). Face f is opposite local node 3 - f.
inline constexpr uint32_t kTetFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};

struct TetFace {
  std::array<uint32_t, 3> key;  // the face's node indices, ascending
  uint32_t order;               // tet * 4 + local face (kTetFaces)
  uint32_t tet() const { return order / 4; }
};

// Whether two faces have the same nodes (element by element: std::array's == calls memcmp).
inline bool same_face(const TetFace& x, const TetFace& y) {
  return x.key[0] == y.key[0] && x.key[1] == y.key[1] && x.key[2] == y.key[2];
}

// Every face of every tet (4 per tet in `tets`), sorted by key and then order: the tets that share
// a face are neighbours in the result, in tet order.
std::vector<TetFace> sorted_tet_faces(const std::vector<uint32_t>& tets);

// mesh.triangles = the faces used by one tet only, each wound outward from its tet, in tet order
// (dimension 3).
void build_boundary(VolumeMesh& mesh);

// mesh.triangles = the faces `orders` (tet * 4 + local face, each once), wound outward from their
// tets, in tet order: build_boundary's result when `orders` are the faces used by one tet.
void set_boundary(VolumeMesh& mesh, std::vector<uint32_t> orders);

// mesh.edges = the unique undirected edges (i < j, sorted) of the tets (dimension 3), else of the
// quads, else of the triangles.
void build_edges(VolumeMesh& mesh);

}  // namespace tacta::mesh_detail
