// Every volume file cut short, at many offsets, must give an InputError: never a crash, a hang or
// another exception (the suite also runs under AddressSanitizer).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>
#include <unistd.h>
#include <vector>

#include "mesh_test_support.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class Truncated : public ::testing::TestWithParam<std::string> {};

TEST_P(Truncated, EveryCutIsAnInputError) {
  const std::string source = GetParam();
  const std::string bytes = read_all(source);
  ASSERT_FALSE(bytes.empty()) << source;
  EXPECT_NO_THROW(load_volume(source));
  // Cuts before the last non-blank byte: the end of the data is always missing.
  const size_t last = bytes.find_last_not_of(" \t\r\n");
  constexpr size_t kCuts = 100;  // evenly spread cuts per file (each costs a file write, a few ms)
  constexpr size_t kTail = 40;   // and every cut among the last bytes, where the end markers are
  const size_t step = std::max<size_t>(1, last / kCuts);
  const std::string cut_path = (std::filesystem::temp_directory_path() /
                                ("tacta_truncated_" + std::to_string(::getpid()) + "_" +
                                 std::filesystem::path(source).filename().string()))
                                   .string();
  size_t cuts = 0;
  std::vector<size_t> offsets;
  for (size_t offset = 0; offset < last; offset += step) offsets.push_back(offset);
  for (size_t offset = step / 2; offset < last && step > 1; offset += 7 * step)
    offsets.push_back(offset);  // off the rhythm
  for (size_t offset = last > kTail ? last - kTail : 0; offset < last; ++offset)
    offsets.push_back(offset);
  for (size_t cut : offsets) {
    {
      std::ofstream out(cut_path, std::ios::binary | std::ios::trunc);
      out.write(bytes.data(), static_cast<std::streamsize>(cut));
    }
    ++cuts;
    try {
      load_volume(cut_path);
      ADD_FAILURE() << source << " cut at byte " << cut << " loaded without an error";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, cut_path);
    } catch (const std::exception& e) {
      ADD_FAILURE() << source << " cut at byte " << cut << ": not an InputError: " << e.what();
    }
  }
  std::filesystem::remove(cut_path);
  EXPECT_GE(cuts, std::min<size_t>(last, kCuts));
}

INSTANTIATE_TEST_SUITE_P(
    Files, Truncated,
    ::testing::Values(test::asset_mesh("liver.msh"), test::asset_mesh("msh4_cube.msh"),
                      test::asset_mesh("cube_low_res.msh"), test::asset_mesh("Bunny.vtk"),
                      test::asset_mesh("Armadillo_Tetra_4406.vtu"), test::test_mesh("cube_v22.msh"),
                      test::test_mesh("cube_legacy.vtk"), test::test_mesh("cube_ascii.vtu"),
                      test::test_mesh("cube_binary32.vtu"), test::test_mesh("cube_binary64_be.vtu"),
                      test::test_mesh("cube_zlib.vtu"),
                      test::test_mesh("vtk9/cube_tets_binary.vtk"),
                      test::test_mesh("vtk9/cube_tets_raw.vtu")),
    [](const ::testing::TestParamInfo<std::string>& param_info) {
      std::string name = std::filesystem::path(param_info.param).filename().string();
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

// Surface files have no end marker (a cut OBJ is a smaller valid OBJ), so a cut surface may load;
// what it must never do is crash or throw anything but InputError.
class TruncatedSurface : public ::testing::TestWithParam<std::string> {};

TEST_P(TruncatedSurface, LoadsOrGivesAnInputError) {
  const std::string source = GetParam();
  const std::string bytes = read_all(source);
  ASSERT_FALSE(bytes.empty()) << source;
  constexpr size_t kCuts = 30;  // assimp is slower to start than the volume readers
  const std::string cut_path = (std::filesystem::temp_directory_path() /
                                ("tacta_truncated_" + std::to_string(::getpid()) + "_" +
                                 std::filesystem::path(source).filename().string()))
                                   .string();
  size_t errors = 0;
  for (size_t i = 0; i < kCuts; ++i) {
    const size_t cut = bytes.size() * i / kCuts;
    {
      std::ofstream out(cut_path, std::ios::binary | std::ios::trunc);
      out.write(bytes.data(), static_cast<std::streamsize>(cut));
    }
    try {
      SurfaceMesh s = load_surface(cut_path);
      EXPECT_GT(s.triangle_count(), 0u);
      for (uint32_t index : s.triangles) ASSERT_LT(index, s.vertex_count());
    } catch (const InputError&) {
      ++errors;
    } catch (const std::exception& e) {
      ADD_FAILURE() << source << " cut at byte " << cut << ": not an InputError: " << e.what();
    }
  }
  std::filesystem::remove(cut_path);
  EXPECT_GT(errors, 0u);  // at least the empty file is refused
}

INSTANTIATE_TEST_SUITE_P(
    Files, TruncatedSurface,
    ::testing::Values(test::asset_mesh("liver.obj"), test::asset_mesh("Bunny.stl"),
                      test::test_mesh("tetra.ply"), test::test_mesh("tetra.gltf"),
                      test::test_mesh("tetra.glb"), test::test_mesh("pyramid_coff.off"),
                      test::test_mesh("pyramid_ascii.vtk"), test::test_mesh("pyramid_binary.vtk"),
                      test::test_mesh("pyramid_zlib_blocks.vtp"),
                      test::test_mesh("pyramid_appended_raw64.vtp"),
                      test::test_mesh("pyramid_appended_base64.vtp"),
                      test::test_mesh("vtk9/sphere_strips_default.vtp"),
                      test::test_mesh("vtk9/sphere_strips_binary.vtk")),
    [](const ::testing::TestParamInfo<std::string>& param_info) {
      std::string name = std::filesystem::path(param_info.param).filename().string();
      for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
      return name;
    });

}  // namespace
}  // namespace tacta
