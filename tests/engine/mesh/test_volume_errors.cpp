// Broken mesh files (volume and surface): each gives an InputError that names the file, the line
// when there is one, and what was wrong. Files under fuzz/ are inputs the fuzzers found.
#include <gtest/gtest.h>
#include <string>

#include "mesh_test_support.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

using test::test_mesh;

struct BrokenCase {
  const char* file;
  int line;              // expected line, 0 when the error has none
  const char* fragment;  // a piece of the message
  bool surface = false;  // load_surface instead of load_volume
};

class BrokenVolume : public ::testing::TestWithParam<BrokenCase> {};

TEST_P(BrokenVolume, GivesAClearInputError) {
  const BrokenCase& c = GetParam();
  const std::string path = test_mesh(c.file);
  try {
    if (c.surface) {
      load_surface(path);
    } else {
      load_volume(path);
    }
    FAIL() << c.file << " loaded without an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, path);
    EXPECT_EQ(e.where().line, c.line) << e.what();
    EXPECT_NE(std::string(e.what()).find(c.fragment), std::string::npos) << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Files, BrokenVolume,
    ::testing::Values(
        BrokenCase{"broken_node_count.msh", 15, "only 9 nodes"},
        BrokenCase{"broken_element_count.msh", 24, "only 6 elements"},
        BrokenCase{"broken_index.msh", 20, "refers to node 42"},
        BrokenCase{"broken_nan.msh", 9, "finite"}, BrokenCase{"broken_inf.vtk", 11, "finite"},
        BrokenCase{"broken_flat_tet.msh", 0, "tet 6"},
        BrokenCase{"broken_no_tets.msh", 0, "no tetrahedra"},
        BrokenCase{"broken_short_line.msh", 18, "fewer node numbers"},
        BrokenCase{"broken_unknown.dat", 1, "unknown volume mesh format"},
        BrokenCase{"broken_empty.msh", 0, "empty"},
        BrokenCase{"broken_cell_index.vtk", 15, "refers to point 60"},
        BrokenCase{"broken_cell_type.vtk", 15, "must have 8 points"},
        BrokenCase{"broken_types.vtu", 17, "must hold 7 values"},
        BrokenCase{"broken_base64.vtu", 6, "base64"}, BrokenCase{"broken_header.vtu", 6, "header"},
        BrokenCase{"broken_mesh_format.msh", 2, "version 3.0"},
        BrokenCase{"does_not_exist.msh", 0, "cannot open"},
        BrokenCase{"broken_duplicate_element.msh", 21,
                   "element 3 is defined twice (first on line 20)"},
        BrokenCase{"broken_ply_index.ply", 16, "vertex index 7 is out of range", true},
        BrokenCase{"broken_ply_empty_face.ply", 15, "at least 3 vertex indices, found 0", true},
        BrokenCase{"broken_ply_header.ply", 9, "expected a PLY header line", true},
        BrokenCase{"broken_ply_count.ply", 3, "declares 1000000000 items", true},
        BrokenCase{"broken_ply_number.ply", 13, "found 'abc'", true},
        BrokenCase{"fuzz/ply_binary_index_postprocess.ply", 0,
                   "item 3: vertex index 33554432 is out of range", true},
        BrokenCase{"broken_obj_number.obj", 4, "found 'abc'", true},
        BrokenCase{"broken_obj_inf.obj", 4, "found '.inf'", true},
        BrokenCase{"broken_obj_index.obj", 7, "vertex index 9 is out of range", true},
        BrokenCase{"broken_stl_number.stl", 13, "found '1e'", true},
        BrokenCase{"broken_surface.dae", 0, "unsupported surface format '.dae'", true},
        BrokenCase{"broken_obj_named_gltf.gltf", 0, "the glTF JSON does not parse", true},
        BrokenCase{"fuzz/gltf_strip_without_positions.gltf", 0,
                   "primitive 0 has no POSITION attribute", true},
        BrokenCase{"broken_off_index.off", 15, "vertex index '5' is out of range", true},
        BrokenCase{"broken_off_count.off", 5, "500 faces, more lines than the file has", true},
        BrokenCase{"broken_off_number.off", 8, "found 'zero'", true},
        BrokenCase{"broken_off_4off.off", 3, "4OFF and nOFF", true},
        BrokenCase{"broken_polydata_index.vtk", 16, "cell 0 refers to point 9", true},
        BrokenCase{"broken_polydata_short.vtk", 20, "TRIANGLE_STRIPS says its cell list holds 10",
                   true},
        BrokenCase{"broken_polydata_binary.vtk", 9, "ends before its 10 binary values", true},
        BrokenCase{"broken_strip.vtp", 12, "strip 0 has 2 points", true},
        BrokenCase{"broken_zlib_size.vtp", 11, "cannot inflate to the 999999984 bytes", true},
        BrokenCase{"broken_appended_offset.vtp", 9, "offset inside the appended data", true},
        BrokenCase{"pyramid_ascii.vtk", 4, "DATASET POLYDATA is a surface"}),
    [](const ::testing::TestParamInfo<BrokenCase>& param_info) {
      std::string name = param_info.param.file;
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

TEST(VolumeErrors, FinalizeRejectsIndicesOutOfRange) {
  VolumeMesh mesh;
  mesh.source = "hand-made";
  mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  mesh.tets = {0, 1, 2, 4};
  EXPECT_THROW(finalize(mesh), InputError);
}

TEST(VolumeErrors, FinalizeNamesTheFlatTet) {
  VolumeMesh mesh;
  mesh.source = "hand-made";
  mesh.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  mesh.tets = {0, 1, 2, 3};
  try {
    finalize(mesh);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("hand-made: tet 0"), std::string::npos) << e.what();
  }
}

TEST(VolumeErrors, SurfaceFileIsNotAVolume) {
  EXPECT_THROW(load_volume(test::asset_mesh("liver.obj")), InputError);
}

TEST(VolumeErrors, BadPrimitivesAreInputErrors) {
  EXPECT_THROW(make_box_grid({1, 0, 1}, {1, 1, 1}, {0, 0, 0}), InputError);
  EXPECT_THROW(make_box_grid({1, 1, 1}, {1, 0, 1}, {0, 0, 0}), InputError);
  EXPECT_THROW(make_box_grid({1, 1, 1}, {100000, 100000, 1}, {0, 0, 0}), InputError);
  EXPECT_THROW(make_sphere(-1, {0, 0, 0}, 2), InputError);
  EXPECT_THROW(make_sphere(1, {0, 0, 0}, 9), InputError);
}

}  // namespace
}  // namespace tacta
