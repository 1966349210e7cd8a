#include "tacta/render/image.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>
#include <system_error>

#include "tacta/error.hpp"

namespace tacta::render {

void write_png(const std::filesystem::path& file, const Image& image) {
  const size_t expected = static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4;
  if (image.width <= 0 || image.height <= 0 || image.rgba.size() != expected)
    throw InputError(SourceLocation{file.string(), 0, 0, ""},
                     "image to write is " + std::to_string(image.width) + "x" +
                         std::to_string(image.height) + " with " +
                         std::to_string(image.rgba.size()) + " bytes; expected " +
                         std::to_string(expected));
  if (file.has_parent_path()) {
    std::error_code ignored;
    std::filesystem::create_directories(file.parent_path(), ignored);
  }
  if (stbi_write_png(file.string().c_str(), image.width, image.height, 4, image.rgba.data(),
                     image.width * 4) == 0)
    throw InputError(SourceLocation{file.string(), 0, 0, ""},
                     "cannot write the PNG (directory missing or not writable?)");
}

Image read_png(const std::filesystem::path& file) {
  int width = 0;
  int height = 0;
  int channels = 0;
  unsigned char* pixels = stbi_load(file.string().c_str(), &width, &height, &channels, 4);
  if (pixels == nullptr)
    throw InputError(SourceLocation{file.string(), 0, 0, ""},
                     std::string("cannot read as PNG: ") + stbi_failure_reason());
  Image image;
  image.width = width;
  image.height = height;
  image.rgba.assign(pixels, pixels + static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
  stbi_image_free(pixels);
  return image;
}

std::string ImageComparison::summary() const {
  if (!same_size) return "image sizes differ";
  char text[160];
  std::snprintf(
      text, sizeof text, "%zu of %zu pixels differ (%.4f%%), largest channel difference %d/255",
      differing_pixels, total_pixels,
      total_pixels
          ? 100.0 * static_cast<double>(differing_pixels) / static_cast<double>(total_pixels)
          : 0.0,
      max_channel_difference);
  return text;
}

ImageComparison compare_images(const Image& actual, const Image& expected,
                               const CompareTolerance& tolerance) {
  ImageComparison result;
  result.same_size = actual.width == expected.width && actual.height == expected.height &&
                     actual.rgba.size() == expected.rgba.size() && !actual.empty();
  if (!result.same_size) return result;
  result.total_pixels = actual.rgba.size() / 4;
  result.difference.width = actual.width;
  result.difference.height = actual.height;
  result.difference.rgba.assign(actual.rgba.size(), 0);
  for (size_t p = 0; p < result.total_pixels; ++p) {
    int worst = 0;
    for (size_t c = 0; c < 4; ++c)
      worst =
          std::max(worst, std::abs(int{actual.rgba[4 * p + c]} - int{expected.rgba[4 * p + c]}));
    result.max_channel_difference = std::max(result.max_channel_difference, worst);
    uint8_t* out = &result.difference.rgba[4 * p];
    // Dim grey copy of the expected picture, differences amplified on top, failures pure red.
    const uint8_t grey = static_cast<uint8_t>(
        (int{expected.rgba[4 * p]} + expected.rgba[4 * p + 1] + expected.rgba[4 * p + 2]) / 12);
    if (worst > tolerance.channel_tolerance) {
      ++result.differing_pixels;
      out[0] = 255;
      out[1] = out[2] = 0;
    } else {
      const uint8_t amplified = static_cast<uint8_t>(std::min(255, grey + worst * 20));
      out[0] = out[1] = amplified;
      out[2] = grey;
    }
    out[3] = 255;
  }
  result.matches = static_cast<double>(result.differing_pixels) <=
                   tolerance.max_differing_fraction * static_cast<double>(result.total_pixels);
  return result;
}

GoldenResult compare_with_golden(const Image& actual, const std::filesystem::path& golden,
                                 const std::filesystem::path& out_dir,
                                 const CompareTolerance& tolerance) {
  GoldenResult result;
  const std::string stem = golden.stem().string();
  Image expected;
  std::string problem;
  if (!std::filesystem::exists(golden)) {
    problem = "golden image missing: " + golden.string() + " (run scripts/regen-goldens)";
  } else {
    expected = read_png(golden);
    result.comparison = compare_images(actual, expected, tolerance);
    if (result.comparison.matches) {
      result.message = stem + ": matches (" + result.comparison.summary() + ")";
      return result;
    }
    problem = stem + ": " + result.comparison.summary();
    if (!result.comparison.same_size)
      problem += " (actual " + std::to_string(actual.width) + "x" + std::to_string(actual.height) +
                 ", golden " + std::to_string(expected.width) + "x" +
                 std::to_string(expected.height) + ")";
  }
  result.actual_file = out_dir / (stem + ".actual.png");
  write_png(result.actual_file, actual);
  problem += "; wrote " + result.actual_file.string();
  if (!result.comparison.difference.empty()) {
    result.diff_file = out_dir / (stem + ".diff.png");
    write_png(result.diff_file, result.comparison.difference);
    problem += " and " + result.diff_file.string();
  }
  result.message = problem;
  return result;
}

}  // namespace tacta::render
