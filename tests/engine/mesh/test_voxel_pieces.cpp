// What the voxeliser makes of thin and split shapes: one piece per surface shell, the volume kept,
// and the warnings a user reads (tacta run, mesh-info).
#include <cmath>
#include <gtest/gtest.h>
#include <string>

#include "mesh_test_support.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

bool has_warning(const LoadReport& r, const std::string& words) {
  for (const std::string& w : r.warnings)
    if (w.find(words) != std::string::npos) return true;
  return false;
}

MeshSourceDesc surface_body(const std::string& path, double voxel_size = 0) {
  MeshSourceDesc desc;
  desc.path = path;
  desc.voxel_size = voxel_size;
  return desc;
}

// SOFA's simplified Armadillo: at diagonal / 20 the inside cells split an arm off (the old
// automatic size let that piece fall freely); the automatic size now refines until it holds.
TEST(VoxelPieces, AutomaticSizeKeepsTheArmadilloInOnePiece) {
  LoadReport r;
  const VolumeMesh body =
      load_body_mesh(surface_body(test::test_mesh("Armadillo_verysimplified.obj")), &r);
  EXPECT_EQ(r.shells, 1u);
  ASSERT_EQ(r.piece_volumes.size(), 1u);
  EXPECT_EQ(piece_volumes(body).size(), 1u);
  EXPECT_TRUE(has_warning(r, "made 2 times 1.5x finer")) << r.warnings.size();
  EXPECT_NEAR(r.mesh_volume / r.enclosed_volume, 1.0, 0.05);  // 98.9% measured
  EXPECT_NEAR(test::total_volume(body), r.mesh_volume, 1e-9 * r.mesh_volume);
  EXPECT_NE(describe_body_mesh(body, r).find("1 piece(s) from 1 surface shell(s)"),
            std::string::npos);
}

// A voxel size the user gives is kept: the pieces it would cut are joined by the crossed cells.
TEST(VoxelPieces, GivenSizeJoinsThePiecesWithTheCrossedCells) {
  LoadReport r;
  const VolumeMesh body =
      load_body_mesh(surface_body(test::test_mesh("Armadillo_verysimplified.obj"), 0.6263), &r);
  EXPECT_EQ(r.split_pieces, 2u);
  EXPECT_EQ(r.piece_volumes.size(), 1u);
  EXPECT_TRUE(has_warning(r, "fell into 2 pieces for 1 surface shell"));
  EXPECT_TRUE(has_warning(r, "of the volume the surface encloses"));  // 186%: the price of the join
  EXPECT_DOUBLE_EQ(r.voxel_size, 0.6263);
}

// Thin parts: the automatic size follows volume / area, not only the bounding box, so the thin
// dental instrument (an open surface) keeps its volume and its whole length.
TEST(VoxelPieces, ThinInstrumentKeepsItsVolume) {
  LoadReport r;
  const VolumeMesh body =
      load_body_mesh(surface_body(test::test_mesh("dental_instrument_light.obj")), &r);
  EXPECT_TRUE(has_warning(r, "not closed"));
  EXPECT_EQ(r.piece_volumes.size(), 1u);
  EXPECT_GT(r.mesh_volume, 0.9 * r.enclosed_volume);  // 114% measured; diagonal / 20 kept 2 cells
  const MeshQuality q = mesh_quality(body);
  const double diagonal =
      std::hypot(q.bounds_max[0] - q.bounds_min[0], q.bounds_max[1] - q.bounds_min[1],
                 q.bounds_max[2] - q.bounds_min[2]);
  EXPECT_LT(r.voxel_size, diagonal / 50);
}

// Volume files: pieces are counted too, and a mesh in two pieces is said to be one.
TEST(VoxelPieces, TwoTetsApartAreTwoPieces) {
  VolumeMesh two;
  two.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 5, 0, 0, 6, 0, 0, 5, 1, 0, 5, 0, 1};
  two.tets = {0, 1, 2, 3, 4, 5, 6, 7};
  finalize(two);
  const std::vector<double> pieces = piece_volumes(two);
  ASSERT_EQ(pieces.size(), 2u);
  EXPECT_NEAR(pieces[0], 1.0 / 6.0, 1e-15);
  EXPECT_EQ(piece_volumes(load_volume(test::asset_mesh("liver.msh"))).size(), 1u);
}

}  // namespace
}  // namespace tacta
