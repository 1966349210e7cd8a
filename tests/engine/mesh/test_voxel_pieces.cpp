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

// voxel_size 0: the automatic size, here with the largest tet budget, so that the thin parts
// decide it (the default budget's coarser bodies: test_tet_budget.cpp).
MeshSourceDesc surface_body(const std::string& path, double voxel_size = 0) {
  MeshSourceDesc desc;
  desc.path = path;
  desc.voxel_size = voxel_size;
  if (voxel_size == 0) desc.max_tets = kMaxTetsLimit;
  return desc;
}

// SOFA's simplified Armadillo: at diagonal / 20 the inside cells split an arm off (the old
// automatic size let that piece fall freely); the automatic size now refines until it holds.
TEST(VoxelPieces, AutomaticSizeKeepsTheArmadilloInOnePiece) {
  LoadReport r;
  const VolumeMesh body =
      load_body_mesh(surface_body(test::test_mesh("Armadillo_verysimplified.obj")), &r);
  EXPECT_EQ(r.max_tets, static_cast<size_t>(kMaxTetsLimit));
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

// The tet budget (max_tets): a surface file without voxel_size or tetrahedralize.max_volume
// becomes a body the default model steps every 1 kHz tick; thin parts stay joined, the fine
// surface stays embedded, and the user is told when the budget made the body coarser.
// max_tets 0: the default budget.
MeshSourceDesc budget_body(const std::string& path, int64_t max_tets = 0) {
  MeshSourceDesc desc;
  desc.path = path;
  desc.max_tets = max_tets;
  return desc;
}

// SOFA's Armadillo has thin fingers and ears: its thin parts ask for 63,174 voxel tets (and a
// detailed animal for 311,262, which did not step 0.2 s in 300 s). By default the body fits the
// budget, in one piece, with every vertex of the fine surface embedded.
TEST(TetBudget, DetailedSurfaceFitsTheDefaultBudgetInOnePiece) {
  LoadReport r;
  const std::string path = test::test_mesh("Armadillo_verysimplified.obj");
  const VolumeMesh body = load_body_mesh(budget_body(path), &r);
  EXPECT_LE(body.tet_count(), static_cast<size_t>(kDefaultMaxTets));
  // Not needlessly coarse: the arm splits off at most sizes near the budget (the join would
  // triple the volume), so 426 tets at 1.33 m were kept.
  EXPECT_GT(body.tet_count(), static_cast<size_t>(kDefaultMaxTets) / 4);
  EXPECT_EQ(r.max_tets, static_cast<size_t>(kDefaultMaxTets));
  EXPECT_EQ(piece_volumes(body).size(), 1u);
  EXPECT_GT(r.voxel_size, r.thin_part_size);
  EXPECT_TRUE(has_warning(r, "coarser than the")) << describe_body_mesh(body, r);
  ASSERT_TRUE(body.embedding.has_value());
  EXPECT_EQ(body.embedding->surface.vertex_count(), load_surface(path).vertex_count());
  EXPECT_NE(describe_body_mesh(body, r).find("within max_tets 1000"), std::string::npos);
}

// max_tets overrides the default: a larger budget gives a finer body, still within it.
TEST(TetBudget, MaxTetsOverridesTheDefault) {
  LoadReport small, large;
  const std::string path = test::test_mesh("Armadillo_verysimplified.obj");
  const VolumeMesh coarse = load_body_mesh(budget_body(path, 600), &small);
  const VolumeMesh fine = load_body_mesh(budget_body(path, 8000), &large);
  EXPECT_LE(coarse.tet_count(), 600u);
  EXPECT_LE(fine.tet_count(), 8000u);
  EXPECT_GT(fine.tet_count(), static_cast<size_t>(kDefaultMaxTets));
  EXPECT_LT(large.voxel_size, small.voxel_size);
  EXPECT_EQ(large.max_tets, 8000u);
  EXPECT_EQ(piece_volumes(coarse).size(), 1u);
  EXPECT_EQ(piece_volumes(fine).size(), 1u);
}

// A budget the thin parts fit in: the thin parts' voxel is used as it is, with no warning.
TEST(TetBudget, RoomyBudgetKeepsTheThinPartsSize) {
  LoadReport r;
  const VolumeMesh body = load_body_mesh(budget_body(test::asset_mesh("sphere.obj"), 20000), &r);
  EXPECT_DOUBLE_EQ(r.voxel_size, r.thin_part_size);
  EXPECT_FALSE(has_warning(r, "coarser than the"));
  EXPECT_LE(body.tet_count(), 20000u);
}

// A thin open instrument: no budget-sized cell is mostly inside it, so the cells its surface
// crosses hold it, in one piece, within the budget.
TEST(TetBudget, ThinInstrumentStaysOnePieceWithinTheBudget) {
  LoadReport r;
  const VolumeMesh body =
      load_body_mesh(budget_body(test::test_mesh("dental_instrument_light.obj")), &r);
  EXPECT_LE(body.tet_count(), static_cast<size_t>(kDefaultMaxTets));
  EXPECT_EQ(piece_volumes(body).size(), 1u);
  EXPECT_TRUE(has_warning(r, "the cells it crosses were kept"));
}

// Gmsh without max_volume: the surface as it is when its tets fit, else remeshed to fit with the
// input surface embedded; a given max_volume is kept (no budget).
TEST(TetBudget, TetrahedralizeMeetsTheBudget) {
  MeshSourceDesc liver = budget_body(test::asset_mesh("liver.obj"));
  liver.tetrahedralize = TetrahedralizeDesc{};
  LoadReport as_is;
  const VolumeMesh small = load_body_mesh(liver, &as_is);  // 365 tets: within the budget
  EXPECT_EQ(as_is.budget_max_volume, 0.0);
  EXPECT_FALSE(small.embedding.has_value());

  // 8,535 tets as it is. Its remesh follows 40-degree crease patches, which floor it at 1,058
  // tets whatever max_volume (so the default 1,000 loads with a warning): 3,000 is reachable.
  MeshSourceDesc bunny = budget_body(test::asset_mesh("Bunny.stl"), 3000);
  bunny.tetrahedralize = TetrahedralizeDesc{};
  LoadReport r;
  const VolumeMesh body = load_body_mesh(bunny, &r);
  EXPECT_LE(body.tet_count(), 3000u);
  EXPECT_EQ(r.max_tets, 3000u);
  EXPECT_GT(r.budget_max_volume, 0.0);
  ASSERT_TRUE(body.embedding.has_value());
  EXPECT_EQ(body.embedding->surface.triangle_count(), 2728u);
  EXPECT_NE(describe_body_mesh(body, r).find("remeshed at max_volume"), std::string::npos);
}

TEST(TetBudget, VolumeFileRefusesMaxTets) {
  EXPECT_THROW(load_body_mesh(budget_body(test::asset_mesh("liver.msh"), 1000)), InputError);
}

}  // namespace
}  // namespace tacta
