// `tacta snapshot`: the demo scene at 0.5 s gives a real picture of the requested size; bad times
// are bad input and write nothing.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <set>

#include "cli_process.hpp"
#include "tacta/render/image.hpp"

namespace tacta::test {
namespace {

// Standard deviation of the luminance, of 255: 0 for a blank (single-colour) picture.
double luminance_spread(const render::Image& image) {
  double sum = 0, sum_sq = 0;
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  for (size_t i = 0; i < pixels; ++i) {
    const uint8_t* p = &image.rgba[4 * i];
    const double y = 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
    sum += y;
    sum_sq += y * y;
  }
  const double mean = sum / static_cast<double>(pixels);
  return std::sqrt(std::max(0.0, sum_sq / static_cast<double>(pixels) - mean * mean));
}

TEST(SnapshotCommand, LiverAtHalfASecondIsARealPictureOfTheRequestedSize) {
  const auto dir = fresh_dir("liver");
  const auto png = dir / "liver_0.5s.png";
  const CliResult r = run_tacta({"snapshot", "scenes/liver_palpation.yaml", "--at", "0.5", "--out",
                                 png.string(), "--width", "240", "--height", "160"},
                                dir);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const render::Image image = render::read_png(png);
  EXPECT_EQ(image.width, 240);
  EXPECT_EQ(image.height, 160);
  EXPECT_GT(luminance_spread(image), 5.0);
  std::set<uint32_t> colours;
  for (size_t i = 0; i + 3 < image.rgba.size(); i += 4)
    colours.insert(uint32_t{image.rgba[i]} << 16 | uint32_t{image.rgba[i + 1]} << 8 |
                   image.rgba[i + 2]);
  EXPECT_GT(colours.size(), 50u) << "a shaded body has many colours";
  EXPECT_NE(r.out.find("t = 0.5"), std::string::npos) << r.out;
}

TEST(SnapshotCommand, AFaultedRunExitsOneAndStillWritesThePicture) {
  // tensor_mass's central differences, asked for by name, are unstable at the beam's 1 ms step
  // (the P-wave crosses a 5 cm cell in about 1 ms): the body is frozen within a few ms. (Its
  // default, `auto`, takes implicit Euler there.)
  const auto dir = fresh_dir("faulted");
  const auto png = dir / "beam.png";
  const CliResult r =
      run_tacta({"snapshot", "scenes/examples/beam_under_gravity.yaml", "--at", "0.05", "--set",
                 "bodies.*.model={name: tensor_mass, integrator: central_difference}", "--out",
                 png.string(), "--width", "64", "--height", "48"},
                dir);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("FROZEN"), std::string::npos) << r.out;
  const render::Image image = render::read_png(png);
  EXPECT_EQ(image.width, 64);
  EXPECT_EQ(image.height, 48);
}

TEST(SnapshotCommand, NegativeTimeIsBadInputAndWritesNothing) {
  const auto dir = fresh_dir("negative_time");
  const auto png = dir / "never.png";
  const CliResult r = run_tacta(
      {"snapshot", "scenes/liver_palpation.yaml", "--at=-0.5", "--out", png.string()}, dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("--at"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(png));
}

TEST(SnapshotCommand, ZeroWidthIsBadInput) {
  const auto dir = fresh_dir("zero_width");
  const CliResult r = run_tacta({"snapshot", "scenes/liver_palpation.yaml", "--at", "0.1", "--out",
                                 (dir / "x.png").string(), "--width", "0"},
                                dir);
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("--width"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace tacta::test
