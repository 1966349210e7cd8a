// A surface file made into a body of at most max_tets tets, so that the default model steps it
// every 1 kHz tick: the automatic voxel size, or a Gmsh max_volume, chosen to meet the budget.
#pragma once

#include <cstddef>

#include "tacta/mesh.hpp"
#include "tacta/mesh_io.hpp"
#include "tacta/scene.hpp"

namespace tacta::mesh_detail {

// The voxel the surface's thin parts ask for: the bounding-box diagonal / 20, or volume / area
// when smaller (half a slab's thickness, a quarter of a rod's diameter). 0 for a flat surface.
double thin_part_voxel_size(const SurfaceMesh& surface);

// Majority-filled voxels of edge max(thin parts, budget), made coarser until the tets fit
// max_tets. Each surface shell stays one piece (a finer grid where the budget allows it, else the
// crossed cells join the pieces: voxelize's guarantee). Fills report's max_tets and
// thin_part_size, and warns when the budget made the voxels coarser than the thin parts.
VolumeMesh voxelize_within_budget(const SurfaceMesh& surface, size_t max_tets, LoadReport& report);

// Gmsh's tets of the surface as it is; past max_tets, remeshed with a max_volume chosen to fit
// (report.budget_max_volume), the input surface then embedded in the tets for drawing and touch.
VolumeMesh tetrahedralize_within_budget(const SurfaceMesh& surface,
                                        const TetrahedralizeDesc& options, size_t max_tets,
                                        LoadReport& report);

}  // namespace tacta::mesh_detail
