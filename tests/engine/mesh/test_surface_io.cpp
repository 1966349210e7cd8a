// Surfaces through assimp: each format, welding across sub-meshes, degenerate triangles, errors.
#include <cmath>
#include <gtest/gtest.h>

#include "mesh_test_support.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

using test::asset_mesh;
using test::test_mesh;

double min_coordinate(const SurfaceMesh& s, size_t axis) {
  double m = INFINITY;
  for (size_t v = 0; v < s.vertex_count(); ++v) m = std::min(m, s.positions[3 * v + axis]);
  return m;
}

TEST(SurfaceIo, LiverObjIsClosed) {
  LoadReport report;
  SurfaceMesh s = load_surface(asset_mesh("liver.obj"), &report);
  EXPECT_EQ(s.triangle_count(), 274u);
  EXPECT_TRUE(report.closed());
  // Divergence theorem over the OBJ's own faces (computed independently with Python): 36.5685 m^3.
  EXPECT_NEAR(enclosed_volume(s), 36.56851846758213, 1e-6);  // assimp keeps floats
}

TEST(SurfaceIo, BunnyStlIsWeldedIntoOneClosedSurface) {
  LoadReport report;
  SurfaceMesh s = load_surface(asset_mesh("Bunny.stl"), &report);
  EXPECT_EQ(s.triangle_count() + report.degenerate_triangles, 2728u);
  EXPECT_GT(report.welded_vertices, 0u);  // STL repeats every corner per face
  EXPECT_LT(s.vertex_count(), s.triangle_count());
  EXPECT_GT(std::abs(enclosed_volume(s)), 0.0);
}

TEST(SurfaceIo, AsciiPlyDropsTheDegenerateFace) {
  LoadReport report;
  SurfaceMesh s = load_surface(test_mesh("tetra.ply"), &report);
  EXPECT_EQ(s.vertex_count(), 4u);
  EXPECT_EQ(s.triangle_count(), 4u);
  EXPECT_EQ(report.degenerate_triangles, 1u);
  EXPECT_FALSE(report.warnings.empty());
  EXPECT_TRUE(report.closed());
  EXPECT_NEAR(enclosed_volume(s), 1.0 / 6.0, 1e-7);
}

TEST(SurfaceIo, GltfAppliesTheNodeTransform) {
  SurfaceMesh s = load_surface(test_mesh("tetra.gltf"));
  EXPECT_EQ(s.vertex_count(), 4u);
  EXPECT_EQ(s.triangle_count(), 4u);
  EXPECT_NEAR(min_coordinate(s, 0), 2.0, 1e-7);
  EXPECT_NEAR(enclosed_volume(s), 1.0 / 6.0, 1e-7);
}

TEST(SurfaceIo, BinaryGlb) {
  SurfaceMesh s = load_surface(test_mesh("tetra.glb"));
  EXPECT_EQ(s.triangle_count(), 4u);
  EXPECT_NEAR(min_coordinate(s, 1), 2.0, 1e-7);
  EXPECT_NEAR(enclosed_volume(s), 1.0 / 6.0, 1e-7);
}

TEST(SurfaceIo, SubMeshesAreMergedAndWelded) {
  LoadReport report;
  SurfaceMesh s = load_surface(test_mesh("two_parts.obj"), &report);
  EXPECT_EQ(s.vertex_count(), 4u);
  EXPECT_EQ(s.triangle_count(), 4u);
  EXPECT_TRUE(report.closed()) << report.boundary_edges;
  EXPECT_NEAR(enclosed_volume(s), 1.0 / 6.0, 1e-12);
}

TEST(SurfaceIo, OpenSurfaceIsReported) {
  LoadReport report;
  load_surface(asset_mesh("stylus.obj"), &report);
  EXPECT_EQ(report.boundary_edges, 4u);  // counted independently from the OBJ faces
  EXPECT_FALSE(report.closed());
}

TEST(SurfaceIo, BrokenFilesAreInputErrors) {
  EXPECT_THROW(load_surface(test_mesh("broken_surface.stl")), InputError);
  EXPECT_THROW(load_surface(test_mesh("no_such_file.obj")), InputError);
  EXPECT_THROW(load_surface(test_mesh("broken_empty.msh")), InputError);
}

}  // namespace
}  // namespace tacta
