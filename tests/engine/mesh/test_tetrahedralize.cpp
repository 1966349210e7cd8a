// Conforming tetrahedra through Gmsh: the boundary is the input surface, the volume is the
// enclosed one, quality is measured, and bad surfaces are refused before Gmsh sees them.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>
#include <set>

#include "mesh_test_support.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

std::set<std::array<double, 3>> points_of(const std::vector<double>& positions) {
  std::set<std::array<double, 3>> out;
  for (size_t i = 0; i + 2 < positions.size(); i += 3)
    out.insert({positions[i], positions[i + 1], positions[i + 2]});
  return out;
}

TEST(Tetrahedralize, BunnyKeepsItsSurfaceAndVolume) {
  LoadReport report;
  const SurfaceMesh bunny = load_surface(test::asset_mesh("Bunny.stl"), &report);
  const VolumeMesh mesh = tetrahedralize(bunny, {}, &report);
  EXPECT_EQ(report.format, "gmsh-tetrahedralize");
  // Conforming to the input: the boundary is the user's triangles, every vertex where it was.
  EXPECT_EQ(mesh.triangles.size(), bunny.triangles.size());
  const auto surface_points = points_of(bunny.positions);
  std::set<uint32_t> boundary_nodes(mesh.triangles.begin(), mesh.triangles.end());
  for (uint32_t n : boundary_nodes) {
    EXPECT_TRUE(surface_points.count(
        {mesh.positions[3 * n], mesh.positions[3 * n + 1], mesh.positions[3 * n + 2]}))
        << "boundary node " << n << " is not a surface vertex";
  }
  LoadReport closed;
  check_closed(test::boundary_of(mesh), closed);
  EXPECT_TRUE(closed.closed());
  EXPECT_NEAR(test::total_volume(mesh), enclosed_volume(bunny), 1e-9 * enclosed_volume(bunny));
  const MeshQuality q = mesh_quality(mesh);
  EXPECT_GT(q.min_volume, 0.0);
  EXPECT_GT(q.min_dihedral_deg, 5.0);   // 11.3 measured with Debian's Gmsh 4.8.4
  EXPECT_GT(q.min_radius_ratio, 0.1);   // 0.28 measured
  EXPECT_GT(q.mean_radius_ratio, 0.6);  // 0.68 measured
}

TEST(Tetrahedralize, MaxVolumeRefinesAndTheQualityAskedForIsChecked) {
  const SurfaceMesh liver = load_surface(test::asset_mesh("liver.obj"));
  TetrahedralizeDesc fine;
  fine.max_volume = 0.01;  // m^3 (liver.obj is about 37 m^3 in its file's units)
  const VolumeMesh coarse_mesh = tetrahedralize(liver, {});
  const VolumeMesh fine_mesh = tetrahedralize(liver, fine);
  EXPECT_GT(fine_mesh.tet_count(), 5 * coarse_mesh.tet_count());
  EXPECT_NEAR(test::total_volume(fine_mesh), enclosed_volume(liver), 0.02 * enclosed_volume(liver));
  // Deterministic: the same surface and options give the same tets (Gmsh's HXT did not).
  const VolumeMesh again = tetrahedralize(liver, fine);
  EXPECT_EQ(again.tet_count(), fine_mesh.tet_count());
  EXPECT_EQ(points_of(again.positions), points_of(fine_mesh.positions));
  EXPECT_EQ(again.tets, fine_mesh.tets);
  TetrahedralizeDesc strict = fine;
  strict.min_dihedral_deg = 40;  // beyond what any Delaunay mesher reaches on a real organ
  try {
    tetrahedralize(liver, strict);
    FAIL() << "an unreachable min_dihedral must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("smallest dihedral angle"), std::string::npos) << e.what();
  }
}

TEST(Tetrahedralize, OpenAndInwardSurfaces) {
  SurfaceMesh open = load_surface(test::asset_mesh("stylus.obj"));  // 4 open edges
  try {
    tetrahedralize(open, {});
    FAIL() << "an open surface must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("4 open edges"), std::string::npos) << e.what();
  }
  SurfaceMesh inward = load_surface(test::asset_mesh("liver.obj"));
  for (size_t t = 0; t < inward.triangle_count(); ++t)
    std::swap(inward.triangles[3 * t + 1], inward.triangles[3 * t + 2]);
  LoadReport report;
  const VolumeMesh mesh = tetrahedralize(inward, {}, &report);
  EXPECT_GT(mesh_quality(mesh).min_volume, 0.0);
  ASSERT_FALSE(report.warnings.empty());
  EXPECT_TRUE(std::any_of(report.warnings.begin(), report.warnings.end(), [](const std::string& w) {
    return w.find("flipped") != std::string::npos;
  }));
  TetrahedralizeDesc bad;
  bad.max_volume = -1;
  EXPECT_THROW(tetrahedralize(load_surface(test::asset_mesh("liver.obj")), bad), InputError);
}

TEST(Tetrahedralize, WrittenMshReadsBack) {
  const VolumeMesh mesh = tetrahedralize(load_surface(test::asset_mesh("liver.obj")), {});
  const std::string path =
      (std::filesystem::path(::testing::TempDir()) / "tacta_liver_tets.msh").string();
  write_gmsh(mesh, path);
  LoadReport report;
  const VolumeMesh back = load_volume(path, &report);
  EXPECT_EQ(report.format, "gmsh-4.1");
  EXPECT_EQ(back.tets, mesh.tets);
  ASSERT_EQ(back.positions.size(), mesh.positions.size());
  for (size_t i = 0; i < back.positions.size(); ++i)
    EXPECT_NEAR(back.positions[i], mesh.positions[i], 1e-12);
}

TEST(Tetrahedralize, SceneBodyFromASurface) {
  MeshSourceDesc desc;
  desc.path = test::asset_mesh("liver.obj");
  desc.scale = {0.01, 0.01, 0.01};  // the liver in cm -> m
  desc.tetrahedralize = TetrahedralizeDesc{};
  LoadReport report;
  const VolumeMesh mesh = load_body_mesh(desc, &report);
  EXPECT_EQ(report.format, "gmsh-tetrahedralize");
  EXPECT_NEAR(test::total_volume(mesh), 36.57e-6, 0.01e-6);
}

}  // namespace
}  // namespace tacta
