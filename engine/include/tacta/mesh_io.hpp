// Loading meshes from files and preparing them for simulation. Every function here throws
// tacta::InputError (file, line when the format is text, what was expected and what was found)
// on bad input, and never crashes on it. Units: whatever the file holds (metres expected);
// load_body_mesh applies the scene's scale and translate.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "tacta/error.hpp"
#include "tacta/mesh.hpp"
#include "tacta/scene.hpp"

namespace tacta {

// What a load or a repair did that the user may want to know; every field is additive.
struct LoadReport {
  std::string format;                 // "gmsh-1", "gmsh-2.2", "gmsh-4.1", "vtk-legacy", "vtk-xml",
                                      // or "surface:<extension>" for assimp imports
  std::vector<std::string> warnings;  // one sentence each, for logs and `tacta mesh-info`
  size_t skipped_elements = 0;        // non-tet elements in a volume file (lines, triangles, hexes)
  size_t inverted_tets = 0;           // negatively oriented tets re-oriented by finalize
  size_t removed_nodes = 0;           // nodes no element references, dropped by finalize
  size_t welded_vertices = 0;         // surface vertices merged with an identical position
  size_t degenerate_triangles = 0;    // zero-area or repeated-index triangles dropped
  size_t boundary_edges = 0;          // surface edges used by one triangle (0 when closed)
  size_t nonmanifold_edges = 0;       // surface edges used by three triangles or more
  bool closed() const { return boundary_edges == 0 && nonmanifold_edges == 0; }
  // What a surface became (voxel_size > 0: voxelised; format "gmsh-tetrahedralize": Gmsh tets).
  double voxel_size = 0;              // m; 0 when the body was not voxelised
  size_t voxel_cells = 0;             // kept cubes, 6 tets each
  size_t shells = 0;                  // connected pieces of the input surface
  double enclosed_volume = 0;         // m^3, inside the input surface
  double mesh_volume = 0;             // m^3, of the tets made from it
  std::vector<double> piece_volumes;  // m^3, one per connected piece of the tets (face-connected)
  size_t split_pieces =
      0;  // > 0: the inside cells fell into this many pieces, joined by the crossed cells
  // The automatic tet budget (max_tets) a surface was sized to, 0 when a size was given
  // (voxel_size, tetrahedralize.max_volume) or the mesh is a volume file or a primitive.
  size_t max_tets = 0;
  double thin_part_size = 0;  // m: the voxel the surface's thin parts ask for (automatic voxels)
  double budget_max_volume = 0;  // m^3: the max_volume chosen to meet the budget (Gmsh), 0: none
};

// One line a person reads: what a surface-made body became (voxel size, counts, volume kept,
// pieces), or the file's format and counts; the warnings are separate (report.warnings).
std::string describe_body_mesh(const VolumeMesh& mesh, const LoadReport& report);

// Which reader a file needs, found from its first bytes (never from its extension); Other for a
// surface file, VTK PolyData included.
enum class MeshFormat { GmshV1, GmshV2, GmshV4, VtkLegacy, VtkXml, Other };
MeshFormat detect_mesh_format(const std::string& path);
const char* mesh_format_name(MeshFormat format);

// A triangle surface from .ply, .obj, .off or VTK PolyData (.vtk legacy, .vtp XML; our own
// readers), .stl (checked, then read by assimp), .gltf or .glb (assimp); other extensions are
// refused. Polygons fanned, strips split; attributes a simulation does not use (texture
// coordinates, normals, colours) that do not parse are dropped with one warning. Every sub-mesh
// merged with its node transform applied, identical positions welded, degenerate triangles
// dropped and counted.
SurfaceMesh load_surface(const std::string& path, LoadReport* report = nullptr);

// A tetrahedral mesh from Gmsh (.msh v1, v2.2 ASCII, v4.1 ASCII) or VTK (legacy ASCII or BINARY
// UNSTRUCTURED_GRID; XML .vtu ascii, inline base64 binary, appended raw or base64,
// zlib-compressed). Tets only are kept; the result is finalized (see finalize).
VolumeMesh load_volume(const std::string& path, LoadReport* report = nullptr);

// Makes a raw mesh ready for a model: unreferenced nodes removed (indices remapped), tets oriented
// positively (an inverted tet gets its last two indices swapped, and its embedding weights with
// them), zero-volume tets rejected, unique sorted edges, outward boundary triangles (dimension 3)
// built. Throws InputError naming the element and mesh.source.
void finalize(VolumeMesh& mesh, LoadReport* report = nullptr);

// Element volumes (m^3, or m^2 when planar), edge lengths, worst aspect ratio, bounds.
MeshQuality mesh_quality(const VolumeMesh& mesh);

// Counts surface edges used by one triangle (holes) or by more than two (non-manifold) into report.
void check_closed(const SurfaceMesh& surface, LoadReport& report);

// Volumes (m^3) of the mesh's connected pieces, largest first: tets joined through shared nodes.
std::vector<double> piece_volumes(const VolumeMesh& mesh);

// Volume enclosed by a closed surface (divergence theorem), m^3; signed: positive when outward.
double enclosed_volume(const SurfaceMesh& surface);

// The mesh a scene body asks for: a primitive, a volume file, or a surface file voxelised with
// desc.voxel_size (0 = automatic: the smaller of the bounding-box diagonal / 20 and the surface's
// volume / area, about two cells across a slab and four across a rod) or tetrahedralized. Applies desc.scale, then
// desc.translate (to surface files before voxelising, so voxel_size is in metres), then finalizes.
VolumeMesh load_body_mesh(const MeshSourceDesc& desc, LoadReport* report = nullptr);

// Lumped node masses, kg, for density rho (kg/m^3): each tet gives rho V / 4 to each of its nodes.
// Planar meshes (unit thickness, 1 m): each quad gives rho A / 4 to each node; when the mesh has
// no quads, each triangle gives rho A / 3 (the triangles of a quad grid only draw its quads).
std::vector<double> lumped_masses(const VolumeMesh& mesh, double density);

}  // namespace tacta
