// Image comparison and PNG round trips: no GL needed.
#include <filesystem>
#include <gtest/gtest.h>

#include "tacta/error.hpp"
#include "tacta/render/image.hpp"

namespace tacta::render {
namespace {

Image solid(int w, int h, uint8_t r, uint8_t g, uint8_t b) {
  Image image{w, h, {}};
  for (int i = 0; i < w * h; ++i) image.rgba.insert(image.rgba.end(), {r, g, b, 255});
  return image;
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::path(TACTA_BINARY_DIR) / "test-output" / "render" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

TEST(ImageCompare, IdenticalImagesMatch) {
  const Image a = solid(100, 100, 10, 20, 30);
  const ImageComparison c = compare_images(a, a);
  EXPECT_TRUE(c.matches);
  EXPECT_EQ(c.differing_pixels, 0u);
  EXPECT_EQ(c.max_channel_difference, 0);
}

TEST(ImageCompare, DifferenceOfFiveIsWithinTolerance) {
  const Image a = solid(100, 100, 10, 20, 30);
  const Image b = solid(100, 100, 15, 15, 35);
  const ImageComparison c = compare_images(a, b);
  EXPECT_TRUE(c.matches);
  EXPECT_EQ(c.max_channel_difference, 5);
}

TEST(ImageCompare, TenPixelsOutOfTenThousandPassElevenFail) {
  const Image expected = solid(100, 100, 100, 100, 100);
  Image actual = expected;
  for (int p = 0; p < 10; ++p)
    actual.rgba[static_cast<size_t>(p) * 4 * 37] = 200;  // 0.1 %: allowed
  EXPECT_TRUE(compare_images(actual, expected).matches);
  actual.rgba[4 * 9999 + 1] = 0;  // one more: 0.11 %
  const ImageComparison c = compare_images(actual, expected);
  EXPECT_FALSE(c.matches);
  EXPECT_EQ(c.differing_pixels, 11u);
  EXPECT_EQ(c.max_channel_difference, 100);
}

TEST(ImageCompare, SizeMismatchNeverMatches) {
  const ImageComparison c = compare_images(solid(10, 10, 0, 0, 0), solid(10, 11, 0, 0, 0));
  EXPECT_FALSE(c.same_size);
  EXPECT_FALSE(c.matches);
}

TEST(Png, RoundTripKeepsEveryByte) {
  Image image = solid(7, 5, 1, 2, 3);
  for (size_t i = 0; i < image.rgba.size(); ++i) image.rgba[i] = static_cast<uint8_t>(i * 7);
  const auto file = scratch("png") / "round_trip.png";
  write_png(file, image);
  const Image back = read_png(file);
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.rgba, image.rgba);
}

TEST(Png, ReadingANonPngNamesTheFile) {
  const auto file = scratch("png_bad") / "not_a.png";
  {
    std::FILE* f = std::fopen(file.string().c_str(), "w");
    std::fputs("hello", f);
    std::fclose(f);
  }
  try {
    read_png(file);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not_a.png"), std::string::npos) << e.what();
  }
}

TEST(Golden, MismatchWritesActualAndDiffImages) {
  const auto dir = scratch("golden_mismatch");
  const auto golden = dir / "case.png";
  write_png(golden, solid(40, 30, 0, 0, 0));
  Image actual = solid(40, 30, 0, 0, 0);
  for (size_t p = 0; p < 40; ++p) actual.rgba[p * 4] = 255;  // first row red: 3.3 % differ
  const GoldenResult r = compare_with_golden(actual, golden, dir / "out");
  EXPECT_FALSE(r.comparison.matches);
  ASSERT_TRUE(std::filesystem::exists(r.actual_file)) << r.message;
  ASSERT_TRUE(std::filesystem::exists(r.diff_file)) << r.message;
  const Image diff = read_png(r.diff_file);
  EXPECT_EQ(diff.rgba[0], 255);  // differing pixel in pure red
  EXPECT_EQ(diff.rgba[1], 0);
  EXPECT_EQ(diff.rgba[4 * 40 * 29], 0);  // untouched pixel of a black image stays black
  EXPECT_EQ(read_png(r.actual_file).rgba, actual.rgba);
  EXPECT_NE(r.message.find("40 of 1200"), std::string::npos) << r.message;
}

TEST(Golden, MatchWritesNothing) {
  const auto dir = scratch("golden_match");
  write_png(dir / "same.png", solid(8, 8, 9, 9, 9));
  const GoldenResult r = compare_with_golden(solid(8, 8, 9, 9, 9), dir / "same.png", dir / "out");
  EXPECT_TRUE(r.comparison.matches) << r.message;
  EXPECT_FALSE(std::filesystem::exists(dir / "out"));
}

TEST(Golden, MissingGoldenFailsAndWritesTheActualImage) {
  const auto dir = scratch("golden_missing");
  const GoldenResult r = compare_with_golden(solid(8, 8, 9, 9, 9), dir / "absent.png", dir);
  EXPECT_FALSE(r.comparison.matches);
  EXPECT_TRUE(std::filesystem::exists(dir / "absent.actual.png"));
  EXPECT_NE(r.message.find("regen-goldens"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace tacta::render
