// The .vtu/.pvd writer: what it writes reads back with the same counts, cells and values, in
// both encodings; bad input names the file and the array.
#include <fstream>
#include <gtest/gtest.h>

#include "tacta/error.hpp"
#include "tacta/output/vtk_writer.hpp"
#include "vtu_reader.hpp"

namespace tacta::output {
namespace {

using testing::read_vtu;

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::path(TACTA_BINARY_DIR) / "test-output" / "vtk" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Two tets sharing the face (1, 2, 3): 5 points.
const std::vector<double> kPoints{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
const std::vector<uint32_t> kTets{0, 1, 2, 3, 1, 2, 3, 4};

class VtuRoundTrip : public ::testing::TestWithParam<VtkEncoding> {};

TEST_P(VtuRoundTrip, CountsCellsAndFieldsReadBack) {
  std::vector<double> displacement(15), velocity(15), stress{1.5e3, -2.25e4};
  for (size_t i = 0; i < 15; ++i) {
    displacement[i] = 1e-3 * static_cast<double>(i) + 1.0 / 3.0 * 1e-6;  // needs all 17 digits
    velocity[i] = -0.5 * static_cast<double>(i);
  }
  VtkGrid grid;
  grid.points = kPoints;
  grid.tets = kTets;
  grid.point_data = {{"displacement", 3, displacement}, {"velocity", 3, velocity}};
  grid.cell_data = {{"stress", 1, stress}};
  const auto file = scratch(GetParam() == VtkEncoding::Ascii ? "ascii" : "base64") / "two_tets.vtu";
  write_vtu(file, grid, GetParam());

  const auto vtu = read_vtu(file);
  EXPECT_EQ(vtu.point_count, 5u);
  EXPECT_EQ(vtu.cell_count, 2u);
  ASSERT_EQ(vtu.arrays.at("Points").values.size(), 15u);
  EXPECT_EQ(vtu.arrays.at("Points").values[14], 1.0);
  EXPECT_EQ(vtu.arrays.at("connectivity").values, (std::vector<double>{0, 1, 2, 3, 1, 2, 3, 4}));
  EXPECT_EQ(vtu.arrays.at("offsets").values, (std::vector<double>{4, 8}));
  EXPECT_EQ(vtu.arrays.at("types").values, (std::vector<double>{10, 10}));  // VTK_TETRA
  EXPECT_EQ(vtu.arrays.at("displacement").components, 3);
  EXPECT_EQ(vtu.arrays.at("displacement").values, displacement);  // bit-exact both ways
  EXPECT_EQ(vtu.arrays.at("velocity").values[7], -3.5);
  EXPECT_EQ(vtu.arrays.at("stress").values, stress);
  EXPECT_NE(vtu.text.find("<CellData>"), std::string::npos);
}

INSTANTIATE_TEST_SUITE_P(Encodings, VtuRoundTrip,
                         ::testing::Values(VtkEncoding::Ascii, VtkEncoding::Base64));

TEST(Vtu, PlanarQuadMeshWritesQuads) {
  VolumeMesh square;  // the paper's unit square as one quad
  square.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  square.quads = {0, 1, 2, 3};
  square.dimension = 2;
  const auto file = scratch("quad") / "square.vtu";
  write_vtu(file, grid_of(square, {}), VtkEncoding::Ascii);
  const auto vtu = read_vtu(file);
  EXPECT_EQ(vtu.cell_count, 1u);
  EXPECT_EQ(vtu.arrays.at("types").values, (std::vector<double>{9}));  // VTK_QUAD
}

TEST(Vtu, Base64OfKnownBytes) {
  // RFC 4648 test vectors, through our decoder, pin the alphabet the writer shares.
  EXPECT_EQ(testing::decode_base64("Zm9vYmFy"),
            (std::vector<uint8_t>{'f', 'o', 'o', 'b', 'a', 'r'}));
  EXPECT_EQ(testing::decode_base64("Zm8="), (std::vector<uint8_t>{'f', 'o'}));
}

TEST(Vtu, FieldOfTheWrongSizeIsAnInputErrorNamingIt) {
  std::vector<double> short_field(14);
  VtkGrid grid;
  grid.points = kPoints;
  grid.tets = kTets;
  grid.point_data = {{"velocity", 3, short_field}};
  try {
    write_vtu(scratch("bad") / "bad.vtu", grid);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("bad.vtu"), std::string::npos) << what;
    EXPECT_NE(what.find("velocity"), std::string::npos) << what;
    EXPECT_NE(what.find("expected 15"), std::string::npos) << what;
  }
}

TEST(Vtu, IndexPastThePointsIsAnInputError) {
  const std::vector<uint32_t> bad{0, 1, 2, 5};
  VtkGrid grid;
  grid.points = kPoints;
  grid.tets = bad;
  EXPECT_THROW(write_vtu(scratch("bad_index") / "x.vtu", grid), InputError);
}

TEST(Pvd, SeriesListsEveryStepWithItsTime) {
  const auto dir = scratch("series");
  VtkSeries series(dir, "beam");
  VtkGrid grid;
  grid.points = kPoints;
  grid.tets = kTets;
  for (int step = 0; step < 3; ++step) series.write(step / 60.0, grid);
  EXPECT_EQ(series.step_count(), 3u);
  EXPECT_TRUE(std::filesystem::exists(dir / "beam_000002.vtu"));
  std::ifstream in(series.pvd_file());
  const std::string pvd((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(pvd.find("type=\"Collection\""), std::string::npos);
  EXPECT_NE(pvd.find("file=\"beam_000000.vtu\""), std::string::npos);
  EXPECT_NE(
      pvd.find("timestep=\"0.033333333333333333\" group=\"\" part=\"0\" file=\"beam_000002.vtu\""),
      std::string::npos)
      << pvd;
}

}  // namespace
}  // namespace tacta::output
