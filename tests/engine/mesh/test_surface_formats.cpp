// OFF and VTK PolyData surfaces (hand-made variants and files VTK 9.1 wrote), binary legacy VTK
// and appended .vtu tets, and the leniency towards attributes a simulation does not use.
#include <gtest/gtest.h>
#include <string>

#include "mesh_test_support.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

using test::test_mesh;

size_t warnings_with(const LoadReport& r, const std::string& fragment) {
  size_t n = 0;
  for (const std::string& w : r.warnings) n += w.find(fragment) != std::string::npos;
  return n;
}

// The square pyramid of make_surface_formats.py: 5 corners, a quad base (2 triangles) and four
// sides, 1/3 m^3 (base 1 m^2, height 1 m).
class Pyramid : public ::testing::TestWithParam<const char*> {};

TEST_P(Pyramid, LoadsClosedAndOutward) {
  LoadReport report;
  const SurfaceMesh s = load_surface(test_mesh(GetParam()), &report);
  EXPECT_EQ(s.vertex_count(), 5u);
  EXPECT_EQ(s.triangle_count(), 6u);
  EXPECT_TRUE(report.closed());
  EXPECT_NEAR(enclosed_volume(s), 1.0 / 3.0, 1e-12);
  EXPECT_TRUE(s.corner_uvs.empty());
}

INSTANTIATE_TEST_SUITE_P(Files, Pyramid,
                         ::testing::Values("pyramid.off", "pyramid_coff.off", "pyramid_noff.off",
                                           "pyramid_cnoff.off", "pyramid_fused.off",
                                           "pyramid_bad_colours.off", "pyramid_ascii.vtk",
                                           "pyramid_binary.vtk", "pyramid_ascii.vtp",
                                           "pyramid_binary.vtp", "pyramid_zlib_blocks.vtp",
                                           "pyramid_appended_raw64.vtp",
                                           "pyramid_appended_base64.vtp"),
                         [](const ::testing::TestParamInfo<const char*>& param_info) {
                           std::string name = param_info.param;
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

TEST(SurfaceFormats, IgnoredCellsAndAttributesGiveOneWarning) {
  LoadReport legacy;
  load_surface(test_mesh("pyramid_ascii.vtk"), &legacy);  // one VERTICES cell, point normals
  EXPECT_EQ(legacy.warnings.size(), 1u);
  EXPECT_EQ(warnings_with(legacy, "1 vertex cells and 0 line cells were ignored"), 1u);
  LoadReport colours;
  load_surface(test_mesh("pyramid_bad_colours.off"), &colours);
  ASSERT_EQ(colours.warnings.size(), 1u);
  EXPECT_EQ(warnings_with(colours, "pyramid_bad_colours.off:8: expected a number, found 'red'"),
            1u);
  LoadReport clean;
  load_surface(test_mesh("pyramid_coff.off"), &clean);
  EXPECT_TRUE(clean.warnings.empty());
}

// An OBJ whose faces name vt and vn while the file has none (exported scans): it loads, without
// texture coordinates, with one warning that says what was ignored and where.
TEST(SurfaceFormats, ObjFaceAttributeIndicesWithoutAttributesAreIgnored) {
  LoadReport report;
  const SurfaceMesh s = load_surface(test_mesh("uv_indices_without_vt.obj"), &report);
  EXPECT_EQ(s.triangle_count(), 4u);
  EXPECT_NEAR(enclosed_volume(s), 1.0 / 6.0, 1e-12);
  EXPECT_TRUE(s.corner_uvs.empty());
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_EQ(warnings_with(report, "texture coordinates (1 problem"), 1u) << report.warnings[0];
  EXPECT_EQ(warnings_with(report, "normals (1 problem"), 1u) << report.warnings[0];
  EXPECT_EQ(warnings_with(report, "texture coordinate index 3 is out of range: the file has 0"),
            1u);
}

TEST(SurfaceFormats, PlyNanNormalsAndOutOfRangeColourAreIgnored) {
  LoadReport report;
  const SurfaceMesh s = load_surface(test_mesh("nan_normals.ply"), &report);
  EXPECT_EQ(s.triangle_count(), 4u);
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_EQ(warnings_with(report, "nan_normals.ply:14: property 'nx'"), 1u) << report.warnings[0];
  EXPECT_EQ(warnings_with(report, "4 problems"), 1u) << report.warnings[0];  // nx ny nz red
}

// VTK 9.1's own writers (vtk9/write_vtk_meshes.py): a 16 x 10 sphere as triangle strips, in every
// encoding, reads to the same surface: 16 * 8 + 2 points and 2 * 16 * 8 triangles.
TEST(SurfaceFormats, EveryVtkWrittenEncodingGivesTheSameSphere) {
  const SurfaceMesh reference = load_surface(test_mesh("vtk9/sphere_strips_ascii.vtp"));
  EXPECT_EQ(reference.vertex_count(), 130u);
  EXPECT_EQ(reference.triangle_count(), 256u);
  for (const char* name :
       {"sphere_strips_default.vtp", "sphere_strips_raw.vtp", "sphere_strips_binary64.vtp",
        "sphere_strips_ascii.vtk", "sphere_strips_binary.vtk"}) {
    LoadReport report;
    const SurfaceMesh s = load_surface(test_mesh(std::string("vtk9/") + name), &report);
    EXPECT_EQ(s.triangles, reference.triangles) << name;
    ASSERT_EQ(s.positions.size(), reference.positions.size()) << name;
    for (size_t i = 0; i < s.positions.size(); ++i)  // the ASCII files print 6 digits
      ASSERT_NEAR(s.positions[i], reference.positions[i], 1e-6) << name;
    EXPECT_TRUE(report.closed()) << name;
    EXPECT_GT(enclosed_volume(s), 0.0) << name;  // strips keep their winding: outward
    EXPECT_TRUE(report.warnings.empty()) << name;
  }
}

TEST(SurfaceFormats, VtkWrittenQuadCubeIsWeldedAndItsLineAndVertexIgnored) {
  for (const char* name : {"vtk9/cube_quads_raw_plain.vtp", "vtk9/cube_quads_binary42.vtk"}) {
    LoadReport report;
    const SurfaceMesh s = load_surface(test_mesh(name), &report);
    EXPECT_EQ(s.vertex_count(), 8u) << name;  // 24 points, one per face corner, welded
    EXPECT_EQ(s.triangle_count(), 12u) << name;
    EXPECT_NEAR(enclosed_volume(s), 1e-3, 1e-9) << name;  // a 0.1 m cube
    EXPECT_EQ(warnings_with(report, "1 vertex cells and 1 line cells were ignored"), 1u) << name;
  }
}

TEST(SurfaceFormats, VtkWrittenTetsInBinaryLegacyAndAppendedXml) {
  for (const char* name : {"vtk9/cube_tets_binary.vtk", "vtk9/cube_tets_raw.vtu"}) {
    const VolumeMesh mesh = load_volume(test_mesh(name));
    EXPECT_EQ(mesh.tet_count(), 6u) << name;
    EXPECT_NEAR(test::total_volume(mesh), 1.0, 1e-12) << name;
  }
}

TEST(SurfaceFormats, PolyDataIsASurfaceAndAGridAVolume) {
  EXPECT_EQ(detect_mesh_format(test_mesh("pyramid_ascii.vtk")), MeshFormat::Other);
  EXPECT_EQ(detect_mesh_format(test_mesh("pyramid_binary.vtp")), MeshFormat::Other);
  EXPECT_EQ(detect_mesh_format(test_mesh("vtk9/cube_tets_binary.vtk")), MeshFormat::VtkLegacy);
  EXPECT_EQ(detect_mesh_format(test_mesh("vtk9/cube_tets_raw.vtu")), MeshFormat::VtkXml);
  try {
    load_volume(test_mesh("pyramid_ascii.vtk"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is a surface"), std::string::npos) << e.what();
  }
  try {
    load_surface(test_mesh("vtk9/cube_tets_raw.vtu"));
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is not PolyData"), std::string::npos) << e.what();
  }
}

// A PolyData body is made exactly as an OFF (or STL, OBJ) body of the same surface is.
TEST(SurfaceFormats, PolyDataBodyIsMadeLikeAnyOtherSurface) {
  MeshSourceDesc off, vtp;
  off.path = test_mesh("pyramid.off");
  vtp.path = test_mesh("pyramid_appended_base64.vtp");
  LoadReport off_report, vtp_report;
  const VolumeMesh a = load_body_mesh(off, &off_report), b = load_body_mesh(vtp, &vtp_report);
  EXPECT_GT(a.tet_count(), 0u);
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.tets, b.tets);
  ASSERT_TRUE(b.embedding.has_value());
  EXPECT_EQ(b.embedding->surface.triangle_count(), 6u);
  EXPECT_EQ(off_report.voxel_size, vtp_report.voxel_size);
}

}  // namespace
}  // namespace tacta
