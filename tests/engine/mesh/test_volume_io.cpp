// Volume files: the SOFA reference meshes and the hand-made unit cube in every supported format.
#include <algorithm>
#include <gtest/gtest.h>
#include <set>
#include <utility>

#include "mesh_test_support.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

using test::asset_mesh;
using test::test_mesh;

// Every finalized volume mesh: positive tets, sorted unique edges, a closed outward boundary whose
// enclosed volume (divergence theorem) equals the sum of the tet volumes.
void expect_consistent(const VolumeMesh& mesh) {
  ASSERT_GT(mesh.tet_count(), 0u);
  MeshQuality q = mesh_quality(mesh);
  EXPECT_GT(q.min_volume, 0.0);
  EXPECT_GE(q.worst_aspect_ratio, 1.0 - 1e-12);
  for (size_t e = 0; e + 2 < mesh.edges.size(); e += 2) {
    EXPECT_LT(mesh.edges[e], mesh.edges[e + 1]);
    EXPECT_LT(std::make_pair(mesh.edges[e], mesh.edges[e + 1]),
              std::make_pair(mesh.edges[e + 2], mesh.edges[e + 3]));
  }
  LoadReport closedness;
  SurfaceMesh boundary = test::boundary_of(mesh);
  check_closed(boundary, closedness);
  EXPECT_TRUE(closedness.closed()) << closedness.boundary_edges << " open edges";
  double volume = test::total_volume(mesh);
  EXPECT_NEAR(enclosed_volume(boundary), volume, 1e-10 * volume);
}

TEST(VolumeIo, LiverGmshV1HoldsOnlyTets) {
  LoadReport report;
  VolumeMesh mesh = load_volume(asset_mesh("liver.msh"), &report);
  EXPECT_EQ(report.format, "gmsh-1");
  EXPECT_EQ(mesh.tet_count(), 596u);  // all 596 elements of the file are 4-node tets (type 4)
  EXPECT_EQ(report.skipped_elements, 0u);
  EXPECT_EQ(mesh.node_count() + report.removed_nodes, 181u);
  expect_consistent(mesh);
}

TEST(VolumeIo, BunnyIsXmlDespiteItsExtension) {
  EXPECT_EQ(detect_mesh_format(asset_mesh("Bunny.vtk")), MeshFormat::VtkXml);
  LoadReport report;
  VolumeMesh mesh = load_volume(asset_mesh("Bunny.vtk"), &report);
  EXPECT_EQ(report.format, "vtk-xml");
  EXPECT_EQ(mesh.tet_count(), 5897u);
  EXPECT_EQ(mesh.node_count() + report.removed_nodes, 1911u);
  expect_consistent(mesh);
}

TEST(VolumeIo, ArmadilloVtu) {
  LoadReport report;
  VolumeMesh mesh = load_volume(asset_mesh("Armadillo_Tetra_4406.vtu"), &report);
  EXPECT_EQ(mesh.tet_count(), 4406u);
  EXPECT_EQ(mesh.node_count() + report.removed_nodes, 1446u);
  expect_consistent(mesh);
}

TEST(VolumeIo, GmshV41UnitCube) {
  LoadReport report;
  VolumeMesh mesh = load_volume(asset_mesh("msh4_cube.msh"), &report);
  EXPECT_EQ(report.format, "gmsh-4.1");
  EXPECT_EQ(mesh.node_count(), 14u);
  EXPECT_EQ(mesh.tet_count(), 24u);
  EXPECT_EQ(report.skipped_elements, 68u - 24u);  // points, lines and triangles of the file
  EXPECT_NEAR(test::total_volume(mesh), 1.0, 1e-12);
  MeshQuality q = mesh_quality(mesh);
  for (int a = 0; a < 3; ++a) {
    EXPECT_DOUBLE_EQ(q.bounds_min[a], 0.0);
    EXPECT_DOUBLE_EQ(q.bounds_max[a], 1.0);
  }
  expect_consistent(mesh);
}

TEST(VolumeIo, GmshV22Cube) {
  LoadReport report;
  VolumeMesh mesh = load_volume(asset_mesh("cube_low_res.msh"), &report);
  EXPECT_EQ(report.format, "gmsh-2.2");
  EXPECT_EQ(mesh.tet_count(), 44u);
  EXPECT_EQ(mesh.node_count(), 26u);
  EXPECT_NEAR(test::total_volume(mesh), 7.0 * 7.0 * 7.0,
              1e-4);  // cube of edge 7 (nodes off by < 1e-6)
  expect_consistent(mesh);
}

// The same unit cube (6 tets, one inverted, one boundary triangle, one unused point) in each format.
class UnitCubeFormats : public ::testing::TestWithParam<const char*> {};

TEST_P(UnitCubeFormats, LoadsAndRepairs) {
  LoadReport report;
  VolumeMesh mesh = load_volume(test_mesh(GetParam()), &report);
  EXPECT_EQ(mesh.tet_count(), 6u);
  EXPECT_EQ(mesh.node_count(), 8u);
  EXPECT_EQ(report.removed_nodes, 1u);
  EXPECT_EQ(report.inverted_tets, 1u);
  EXPECT_NEAR(test::total_volume(mesh), 1.0, 1e-14);
  EXPECT_EQ(mesh.edges.size() / 2, 19u);  // 12 cube edges, 6 face diagonals, 1 main diagonal
  EXPECT_EQ(mesh.triangles.size() / 3, 12u);
  expect_consistent(mesh);
}

INSTANTIATE_TEST_SUITE_P(Formats, UnitCubeFormats,
                         ::testing::Values("cube_v22.msh", "cube_legacy.vtk", "cube_ascii.vtu",
                                           "cube_binary32.vtu", "cube_binary64_be.vtu",
                                           "cube_zlib.vtu"));

TEST(VolumeIo, SkippedNonTetsAreCounted) {
  LoadReport report;
  load_volume(test_mesh("cube_legacy.vtk"), &report);
  EXPECT_EQ(report.skipped_elements, 1u);
  EXPECT_FALSE(report.warnings.empty());
}

TEST(VolumeIo, QualityOfTheUnitCube) {
  VolumeMesh mesh = load_volume(test_mesh("cube_v22.msh"));
  MeshQuality q = mesh_quality(mesh);
  EXPECT_NEAR(q.min_volume, 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(q.max_volume, 1.0 / 6.0, 1e-15);
  EXPECT_NEAR(q.min_edge, 1.0, 1e-15);
  EXPECT_NEAR(q.max_edge, std::sqrt(3.0), 1e-15);
  // Kuhn tet: longest edge sqrt(3), largest face sqrt(2)/2, V = 1/6 -> altitude 1/sqrt(2).
  EXPECT_NEAR(q.worst_aspect_ratio, std::sqrt(3.0) * std::sqrt(2.0) * std::sqrt(2.0 / 3.0), 1e-12);
}

}  // namespace
}  // namespace tacta
