// Cutting a tetrahedral body: the edit a blade's swept surface makes to one body's rest mesh,
// computed against the body's current (deformed) node positions, and the checks every edited
// mesh must pass. Pure functions of their inputs (no engine state): the engine installs the
// result at a tick boundary (world/topology_revision). Units: metres.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tacta/embedded_surface.hpp"
#include "tacta/mesh.hpp"
#include "tacta/sim/cut.hpp"

namespace tacta {

// CutMode (tacta/sim/cut.hpp). Removal (carving): every tet the blade passes through goes, with
// nodes left in no tet. Separation: the body splits along the mesh faces the blade crosses (a face
// is crossed when the segment between the centroids of its two tets passes through a blade
// triangle); nodes on the crossed faces are duplicated so the tets on either side stop sharing
// them. No tet is made or lost, so no sliver appears and the mass is kept exactly; the cut follows
// mesh faces (a staircase no finer than the tets).

// The edit of one cut: the new rest mesh and where each of its nodes and tets came from.
struct TopologyEdit {
  VolumeMesh mesh;                    // finalized: tets, boundary triangles, edges; no embedding
  std::vector<uint32_t> node_source;  // per new node: the old node it continues (copies share it)
  std::vector<uint32_t> tet_source;   // per new tet: the old tet
  std::vector<uint8_t> cut_triangle;  // per new boundary triangle: 1 when the cut exposed it
  size_t tets_removed = 0;            // removal
  size_t nodes_removed = 0;           // removal: nodes left in no tet
  size_t nodes_added = 0;             // separation: copies made
  size_t faces_separated = 0;         // separation: interior faces opened
  bool changed() const noexcept { return tets_removed > 0 || faces_separated > 0; }
};

// The edit blade `triangles` (9 doubles each: three corners, m, in the frame of `positions`) make
// to `rest` (a finalized tet mesh, dimension 3) when the body's nodes stand at `positions` (3 per
// node of rest). `rest_cut_triangle` marks rest's boundary triangles earlier cuts exposed (1 per
// boundary triangle, or empty): they stay marked in the edit's cut_triangle. A blade that misses the body gives an edit with
// changed() false. A removal that would leave no tet removes nothing and sets `refused` with the
// reason. Allocates; O(tets + blade triangles * tets near them).
struct CutResult {
  TopologyEdit edit;
  std::string refused;  // empty: the edit may be installed
};
CutResult cut_mesh(const VolumeMesh& rest, std::span<const uint8_t> rest_cut_triangle,
                   std::span<const double> positions, std::span<const double> triangles,
                   CutMode mode);

// What is wrong with an edited mesh, one line each (empty: nothing): a tet with volume <= 0 at
// rest; a face shared by more than two tets; a boundary triangle list that is not exactly the
// faces with one tet (outward); a node in no tet; an edge list that is not the unique tet edges;
// node and index arrays of the wrong size.
std::vector<std::string> topology_problems(const VolumeMesh& mesh);

// The embedded surface carried over an edit: each vertex follows its tet's new index and nodes
// (vertices whose tet was removed go, with their triangles); a triangle whose corners' tets the
// cut parted (they shared a node before and share none now) goes; each exposed face of the edit
// becomes 3 new vertices bound to its tet (exact weights) and one triangle marked in
// `cut_triangle`. Triangle order: kept ones in their old order, then the cut faces. rest_positions,
// positions and normals are filled at rest (the engine updates them from the nodes).
struct CutSurface {
  EmbeddedSurface surface;
  std::vector<uint8_t> cut_triangle;  // per triangle of `surface`: 1 when made by a cut
};
CutSurface cut_embedded_surface(const EmbeddedSurface& old, std::span<const uint8_t> old_cut,
                                const VolumeMesh& old_mesh, const TopologyEdit& edit);

}  // namespace tacta
