// Cutting a tetrahedral body: the edit a blade's swept surface makes to one body's rest mesh,
// computed against the body's current (deformed) node positions, and the checks every edited
// mesh must pass. Pure functions of their inputs (no engine state): the engine installs the
// result at a tick boundary (world/topology_revision). Units: metres.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tacta/embedded_surface.hpp"
#include "tacta/mesh.hpp"
#include "tacta/sim/cut.hpp"

namespace tacta {

// CutMode (tacta/sim/cut.hpp). Removal (carving): every tet whose inside a blade triangle meets
// goes (a triangle that only touches a face, edge or node, to 1e-12 of the tet's size, does not
// count), with nodes left in no tet. Separation: the body splits along the mesh faces the blade
// crosses (a face is crossed when the segment between the centroids of its two tets passes
// through a blade triangle: a centroid on the blade's plane counts as behind it, a segment through
// a triangle's edge or corner hits it); each node of a crossed face gets one copy per group of its
// tets that still hold together through uncrossed faces around it, so a crack (a blade that ends
// inside the body) opens up to its front and no further. No tet is made or lost, so no sliver
// appears and the mass is kept exactly; the cut follows mesh faces (a staircase no finer than the
// tets). Faces already opened are boundary faces, so cutting there again changes nothing. A blade
// triangle with no area (to round-off) or a non-finite corner cuts nothing, in either mode.

// The edit of one cut: the new rest mesh and where each of its nodes and tets came from.
// Removal keeps the surviving nodes and tets in their old order; separation keeps every node and
// tet where it was (tet_source is the identity) and appends the copies, each of them standing,
// at rest, where its source stands.
struct TopologyEdit {
  VolumeMesh mesh;                    // finalized: tets, boundary triangles, edges; no embedding
  std::vector<uint32_t> node_source;  // per new node: the old node it continues (copies share it)
  std::vector<uint32_t> tet_source;   // per new tet: the old tet
  // per new boundary triangle: 1 when a cut exposed it (this one, or an earlier one marked in
  // rest_cut_triangle)
  std::vector<uint8_t> cut_triangle;
  std::vector<uint8_t> exposed;  // per new boundary triangle: 1 when this edit exposed it
  size_t tets_removed = 0;       // removal
  size_t nodes_removed = 0;      // removal: nodes left in no tet
  size_t nodes_added = 0;        // separation: copies made
  size_t faces_separated = 0;    // separation: interior faces opened (a crossed face whose tets
                                 // still share its 3 nodes, deep inside a crack, is not)
  bool changed() const noexcept { return tets_removed > 0 || faces_separated > 0; }
};

// The edit blade `triangles` (9 doubles each: three corners, m, in the frame of `positions`) make
// to `rest` (a finalized tet mesh, dimension 3) when the body's nodes stand at `positions` (3 per
// node of rest). `rest_cut_triangle` marks rest's boundary triangles earlier cuts exposed (1 per
// boundary triangle, or empty): they stay marked in the edit's cut_triangle. A blade that misses
// the body gives an edit with changed() false (the mesh as it was, every node and tet its own
// source). A removal that would leave no tet, or input that does not fit (positions or marks of
// the wrong size, a node at a NaN or infinite position, a mesh that is not a finalized tet
// mesh), changes nothing and sets `refused` with the reason. Allocates; O(tets log tets + blade
// triangles * tets) cheap box tests, exact tests only where boxes meet (48,000 tets, a
// 2-triangle blade: about 70 ms at -O2).
//
// A crack: separation opens a crossed face only once the faces crossed around one of its nodes
// sever the node's tets into groups, so a blade drawn in strokes (a device's sweep, cut every few
// ms) leaves crossed faces closed at first. `crack` (sorted node triples in rest's numbering)
// lists the faces earlier strokes crossed that are still closed: they count as crossed again.
// The result's `crack` is this stroke's and the earlier ones' faces still closed after the edit,
// sorted, in the edited mesh's numbering: hand it to the next cut. Removal keeps it, renumbered.
using FaceNodes = std::array<uint32_t, 3>;
struct CutResult {
  TopologyEdit edit;
  std::string refused;  // empty: the edit may be installed
  std::vector<FaceNodes> crack;
};
CutResult cut_mesh(const VolumeMesh& rest, std::span<const uint8_t> rest_cut_triangle,
                   std::span<const double> positions, std::span<const double> triangles,
                   CutMode mode, std::span<const FaceNodes> crack = {});

// What is wrong with an edited mesh, one line per kind of fault with a count and the first
// offender (empty: nothing): a tet with volume <= 0 at rest (6 V below 1e-12 of its longest edge
// cubed, as finalize rejects); a face shared by more than two tets; a boundary triangle list that
// is not exactly the faces with one tet, each once, wound outward; a node in no tet; an edge list
// that is not the unique tet edges (smaller node first); node and index arrays of the wrong size,
// indices past the nodes, a dimension other than 3. Found from the tets, not through the builders
// that made the boundary and edges.
std::vector<std::string> topology_problems(const VolumeMesh& mesh);

// The embedded surface carried over an edit: each vertex follows its tet's new index and nodes
// with its weights (vertices whose tet was removed go, with their triangles; vertices no kept
// triangle uses go); a triangle whose corners' tets the cut parted (they shared a node before and
// share none now, or the cut split the piece that held both) goes; each face the edit exposed (a
// boundary face whose source nodes were no boundary face of `old_mesh`) becomes 3 new vertices
// bound to its tet (exact weights: 1 on the face's node) and one triangle marked in
// `cut_triangle`. Triangle order: kept ones in their old order (with their corner_uvs and
// old_cut marks, old_cut: 1 per old triangle or empty), then the cut faces (corner_uvs zero).
// rest_positions, positions and normals are filled at rest (the engine updates them from the
// nodes).
struct CutSurface {
  EmbeddedSurface surface;
  std::vector<uint8_t> cut_triangle;  // per triangle of `surface`: 1 when made by a cut
};
CutSurface cut_embedded_surface(const EmbeddedSurface& old, std::span<const uint8_t> old_cut,
                                const VolumeMesh& old_mesh, const TopologyEdit& edit);

}  // namespace tacta
