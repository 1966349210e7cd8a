// Small meshes built in code, for model tests and benchmarks: a box of tetrahedra, a grid of
// axis-aligned edges (3D) or quads (2D), and the paper's 4-node unit square. Each comes with
// lumped masses and a fixed-node mask, and gives the plain views that create() receives.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "tacta/model_api.h"

namespace tacta::models {

struct TestMesh {
  std::vector<double> positions;    // 3 per node, m
  std::vector<uint32_t> tets;       // 4 per tet, positively oriented
  std::vector<uint32_t> triangles;  // 3 per boundary triangle, outward
  std::vector<uint32_t> quads;      // 4 per quad, counter-clockwise
  std::vector<uint32_t> edges;      // 2 per unique edge, i < j
  std::vector<double> masses;       // 1 per node, kg
  std::vector<uint8_t> fixed;       // 1 per node
  uint32_t dimension = 3;

  uint32_t node_count() const { return static_cast<uint32_t>(positions.size() / 3); }
  tacta_mesh_view view() const;  // points into this object: keep it alive and unchanged
  // What the engine hands a model for this mesh (no host services); `view` (this mesh's) and
  // `material` must outlive the instance. dt in s.
  tacta_model_setup setup(const tacta_mesh_view& view, const tacta_material& material,
                          const tacta_param_value* params, uint32_t param_count, double dt) const;
  // Marks every node whose coordinate `axis` (0 x, 1 y, 2 z) is within tolerance of value.
  void fix_plane(int axis, double value, double tolerance = 1e-9);
  // Mean displacement along `component` of the nodes whose rest coordinate `axis` is within
  // tolerance of value (a beam's tip face), m.
  double mean_displacement_on_plane(const double* positions, int axis, double value, int component,
                                    double tolerance = 1e-9) const;
};

// Material in SI units from (E, nu, rho), with both Lamé and Young filled; no damping.
tacta_material make_material(double youngs_modulus, double poisson_ratio, double density);
// Material from the Lamé coefficients directly (the paper gives lambda and mu).
tacta_material make_material_lame(double lambda, double mu, double density);

// nx*ny*nz cubes of size (sx/nx, sy/ny, sz/nz), each split into 6 tets around a diagonal
// (Kuhn/Freudenthal), each cube the mirror image of its neighbours (symmetric, conforming). Origin at (0,0,0). Node index:
// i + (nx+1) * (j + (ny+1) * k).
// kOneDiagonal: every cube split around the same diagonal (the lattice Van Gelder's rule is
// analysed on; stiffer in bending and not mirror-symmetric).
enum class GridSplit { kSymmetric, kOneDiagonal };
TestMesh box_tet_mesh(std::array<uint32_t, 3> cells, std::array<double, 3> size, double density,
                      GridSplit split = GridSplit::kSymmetric);

// The same nodes joined only by the axis-aligned grid edges (no elements): the Cartesian edge
// graph on which the finite-difference operators are exact. Masses: rho times the dual cell.
TestMesh grid_edge_mesh(std::array<uint32_t, 3> cells, std::array<double, 3> size, double density);

// Planar nx*ny quads of unit thickness (dimension 2), edges = the quad sides. Node index
// i + (nx+1) * j, so the 1x1 grid is SW, SE, NW, NE. Masses: rho (kg/m^2) times the dual area.
TestMesh quad_grid_mesh(uint32_t nx, uint32_t ny, double sx, double sy, double density);

// Unique sorted edges of a tet list.
std::vector<uint32_t> edges_of_tets(const std::vector<uint32_t>& tets);
// Boundary triangles (faces used by one tet), oriented outward.
std::vector<uint32_t> boundary_of_tets(const std::vector<uint32_t>& tets);

// A test mesh with its material and a model of class Model built on it, as the engine would
// (the mesh view, material, masses and fixed mask outlive the model). dt in s.
template <class Model, class Options>
struct ModelOnMesh {
  TestMesh mesh;
  tacta_mesh_view view;
  tacta_material material;
  std::unique_ptr<Model> model;

  ModelOnMesh(TestMesh m, const tacta_material& mat, const Options& options = {}, double dt = 1e-3)
      : mesh(std::move(m)), view(mesh.view()), material(mat) {
    model = std::make_unique<Model>(mesh.setup(view, material, nullptr, 0, dt), options);
  }
};

}  // namespace tacta::models
