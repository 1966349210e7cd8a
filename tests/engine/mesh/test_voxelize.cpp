// The voxeliser: volume against the enclosed volume, conformity, and the embedding.
#include <cmath>
#include <gtest/gtest.h>

#include "mesh_test_support.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

// all_inside: every vertex must lie in its tet (no negative weight); else extrapolation is allowed.
void expect_embedding_reproduces_surface(const VolumeMesh& mesh, bool all_inside = true) {
  ASSERT_TRUE(mesh.embedding.has_value());
  const Embedding& e = *mesh.embedding;
  ASSERT_EQ(e.element.size(), e.surface.vertex_count());
  size_t outside = 0;
  for (size_t v = 0; v < e.element.size(); ++v) {
    ASSERT_LT(e.element[v], mesh.tet_count());
    double sum = 0, p[3] = {0, 0, 0}, lowest = 1;
    for (size_t k = 0; k < 4; ++k) {
      double w = e.weights[4 * v + k];
      sum += w;
      lowest = std::min(lowest, w);
      uint32_t node = mesh.tets[4 * e.element[v] + k];
      for (size_t a = 0; a < 3; ++a) p[a] += w * mesh.positions[3 * node + a];
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    for (size_t a = 0; a < 3; ++a) EXPECT_NEAR(p[a], e.surface.positions[3 * v + a], 1e-10);
    if (lowest < -1e-9) ++outside;
  }
  if (all_inside) {
    EXPECT_EQ(outside, 0u);  // the touched cells are kept, so every vertex is in a tet
  }
}

TEST(Voxelize, LiverVolumeIsBracketedByTheInsideCells) {
  LoadReport report;
  SurfaceMesh liver = load_surface(test::asset_mesh("liver.obj"));
  const double enclosed = enclosed_volume(liver);
  VolumeMesh coarse = voxelize(liver, 0.5, &report);
  VolumeMesh fine = voxelize(liver, 0.25);
  EXPECT_TRUE(report.closed());
  const double v_coarse = test::total_volume(coarse), v_fine = test::total_volume(fine);
  // The grid holds the whole body plus the cells the surface cuts: more than the enclosed volume,
  // and the excess shrinks with the cell (about area * h / 2).
  EXPECT_GT(v_fine, enclosed);
  EXPECT_GT(v_coarse, v_fine);
  EXPECT_LT(v_fine, 1.6 * enclosed);
  RecordProperty("enclosed", std::to_string(enclosed));
  RecordProperty("voxel_0.25", std::to_string(v_fine));
  expect_embedding_reproduces_surface(fine);
  LoadReport boundary;
  check_closed(test::boundary_of(fine), boundary);
  // No holes; cells that meet only along an edge may make it non-manifold there.
  EXPECT_EQ(boundary.boundary_edges, 0u);
}

TEST(Voxelize, MajorityFillKeepsTheEnclosedVolume) {
  LoadReport report;
  SurfaceMesh liver = load_surface(test::asset_mesh("liver.obj"));
  const double enclosed = enclosed_volume(liver);
  VolumeMesh voxels = voxelize(liver, 0.25, &report, VoxelFill::Majority);
  EXPECT_NEAR(test::total_volume(voxels), enclosed, 0.05 * enclosed);
  expect_embedding_reproduces_surface(voxels, false);
  EXPECT_FALSE(report.warnings.empty());  // some vertices are outside and extrapolate
}

TEST(Voxelize, CubeSurfaceGivesItsCells) {
  // A closed cube surface of edge 1 voxelised with cells of 0.3 from -0.15 (half a cell of margin):
  // cells [-0.15, 0.15] ... [0.75, 1.05] hold it, 4 per axis, 64 in all; the fifth lies outside.
  VolumeMesh box = make_box_grid({1, 1, 1}, {1, 1, 1}, {0, 0, 0});
  SurfaceMesh surface = test::boundary_of(box);
  surface.source = "cube";
  VolumeMesh voxels = voxelize(surface, 0.3);
  EXPECT_EQ(voxels.tet_count(), 6u * 64u);
  EXPECT_NEAR(test::total_volume(voxels), 64 * 0.027, 1e-12);
  expect_embedding_reproduces_surface(voxels);
}

TEST(Voxelize, BodyMeshFromASurfaceFileUsesTheAutomaticVoxel) {
  MeshSourceDesc desc;
  desc.kind = MeshSourceDesc::Kind::File;
  desc.path = test::asset_mesh("Bunny.stl");
  desc.scale = {0.001, 0.001, 0.001};
  desc.max_tets = kMaxTetsLimit;  // the thin parts' size, not the tet budget, decides here
  LoadReport report;
  VolumeMesh bunny = load_body_mesh(desc, &report);
  EXPECT_GT(bunny.tet_count(), 0u);
  // Bodies use the majority fill: a few surface vertices lie outside every tet (extrapolated
  // weights), and in exchange the volume, hence the mass, stays close to the enclosed one.
  expect_embedding_reproduces_surface(bunny, /*all_inside=*/false);
  ASSERT_TRUE(bunny.embedding.has_value());
  const double enclosed = enclosed_volume(bunny.embedding->surface);
  double volume = 0;
  for (size_t t = 0; t < bunny.tet_count(); ++t) {
    const double* x[4];
    for (size_t k = 0; k < 4; ++k) x[k] = &bunny.positions[3 * bunny.tets[4 * t + k]];
    const double a1[3] = {x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
    const double a2[3] = {x[2][0] - x[0][0], x[2][1] - x[0][1], x[2][2] - x[0][2]};
    const double a3[3] = {x[3][0] - x[0][0], x[3][1] - x[0][1], x[3][2] - x[0][2]};
    volume += (a1[0] * (a2[1] * a3[2] - a2[2] * a3[1]) - a1[1] * (a2[0] * a3[2] - a2[2] * a3[0]) +
               a1[2] * (a2[0] * a3[1] - a2[1] * a3[0])) /
              6.0;
  }
  EXPECT_NEAR(volume / enclosed, 1.0, 0.10)
      << "voxel body volume " << volume << " m^3, enclosed " << enclosed;
  MeshQuality q = mesh_quality(bunny);
  // Automatic cell: bounding-box diagonal / 20, so each axis spans at most about 20 cells.
  EXPECT_LT((q.bounds_max[0] - q.bounds_min[0]) / q.min_edge, 22.0);
}

TEST(Voxelize, BadCellSizeIsAnInputError) {
  SurfaceMesh liver = load_surface(test::asset_mesh("liver.obj"));
  EXPECT_THROW(voxelize(liver, 0.0), InputError);
  EXPECT_THROW(voxelize(liver, 1e-6), InputError);  // billions of cells
}

}  // namespace
}  // namespace tacta
