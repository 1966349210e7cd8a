// Meshes built in code: the scene primitives and the voxeliser that turns a closed surface into a
// tetrahedral body with the surface embedded in it. Every result is finalized (see mesh_io.hpp).
// Units: metres.
#pragma once

#include <array>

#include "tacta/mesh.hpp"
#include "tacta/mesh_io.hpp"
#include "tacta/scene.hpp"

namespace tacta {

// The most nodes a built-in grid may have: 4 million nodes is far past what a haptic loop steps
// (the 1 kHz demos have hundreds to a few thousand), and keeps a typo from eating the memory.
constexpr int64_t kMaxGridNodes = 4'000'000;

// The tet budget a surface file is sized to when the scene gives no voxel_size (or no
// tetrahedralize.max_volume): the default model (corotational_fem) steps this many tets well
// inside the 1 ms haptic tick on a 2-core machine (docs/SCENES.md has the measured figures).
constexpr int64_t kDefaultMaxTets = 1000;
// The largest max_tets a scene may ask for: the voxeliser's 2 million cells, 6 tets each.
constexpr int64_t kMaxTetsLimit = 12'000'000;

// A box [origin, origin + size] cut into cells[0] x cells[1] x cells[2] hexahedra, each split into
// 6 tets around its diagonal from the (min x, min y, min z) corner to the opposite one, so that
// neighbouring cells share their face diagonals (a conforming mesh). Node index:
// i + (nx+1) * (j + (ny+1) * k), with nx = cells[0], ny = cells[1].
VolumeMesh make_box_grid(const Vec3& size, const std::array<int, 3>& cells, const Vec3& origin);

// The same grid as make_box_grid, named "beam_grid" (a long box, usually clamped at one end).
VolumeMesh make_beam_grid(const Vec3& size, const std::array<int, 3>& cells, const Vec3& origin);

// A planar grid (dimension 2, z = origin z) of cells[0] x cells[1] quads over size[0] x size[1].
// Node index: i + (nx+1) * j; the unit square (1 x 1 cells) is SW(0,0)=0, SE(1,0)=1, NW(0,1)=2,
// NE(1,1)=3. Quads are counter-clockwise seen from +z: (SW, SE, NE, NW). Triangles (for drawing)
// split each quad as (SW, SE, NE), (SW, NE, NW). Edges are the quad sides only (no diagonals).
VolumeMesh make_quad_grid(const Vec3& size, const std::array<int, 3>& cells, const Vec3& origin);

// A tetrahedral ball: a cube grid of 2^(subdivisions+1) cells a side whose nodes are pushed
// radially onto spheres (each cube shell onto the sphere of the same relative radius), so the
// boundary nodes lie on the sphere of the given radius (m) around centre. Each octant splits its
// cells along the diagonal that points away from the centre, so no tet lies flat on a shell.
VolumeMesh make_sphere(double radius, const Vec3& centre, int subdivisions);

// Which cells of the voxel grid become tets.
enum class VoxelFill {
  // Cells whose centre is inside the surface (generalized winding number > 1/2) or that a surface
  // triangle touches: every surface vertex lies in a tet, but the volume exceeds the enclosed one
  // by about (surface area) * cell / 2 (liver.obj, cell 0.25: 1.42 times).
  Cover,
  // Cells with at least 5 of 9 samples (centre and corners) inside: the volume stays close to the
  // enclosed one (liver.obj, cell 0.25: within 3 %); surface vertices outside every tet are bound to
  // the nearest cell's best tet with extrapolated weights.
  Majority,
};

// Fills a closed surface with a sparse grid of cubes of edge cell_size (m), chosen by fill, each
// split into the same 6 conforming tets as make_box_grid. The result carries the Embedding: per
// surface vertex, the tet that holds it and its 4 barycentric weights (they sum to 1 and reproduce
// the vertex). A vertex that no tet holds gets the tet of the nearest kept cell that holds it
// best, with extrapolated weights (some negative). An open surface is voxelised all the same, with
// a warning in report (its inside is then a best guess).
VolumeMesh voxelize(const SurfaceMesh& closed, double cell_size, LoadReport* report = nullptr,
                    VoxelFill fill = VoxelFill::Cover);

// Fills a closed surface with conforming tetrahedra through Gmsh (3D Delaunay, then Gmsh's
// optimiser): the boundary of the result is the surface's own triangles. Throws
// InputError (exit 2) on an open or non-manifold surface, on one Gmsh cannot mesh (self-
// intersecting), and when the quality asked for (options) is not reached; inward-facing surfaces
// are flipped with a warning. report->format becomes "gmsh-tetrahedralize".
VolumeMesh tetrahedralize(const SurfaceMesh& closed, const TetrahedralizeDesc& options,
                          LoadReport* report = nullptr);

// Writes the tets (and nodes) as a Gmsh 4.1 ASCII .msh file through Gmsh; InputError if it cannot.
void write_gmsh(const VolumeMesh& mesh, const std::string& path);

}  // namespace tacta
