// RGBA8 images: PNG files (stb) and the golden-image comparison used by the snapshot tests.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace tacta::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba;  // 4 bytes a pixel, row 0 at the top
  bool empty() const { return rgba.empty(); }
};

// Writes a PNG; throws tacta::InputError naming the file when it cannot.
void write_png(const std::filesystem::path& file, const Image& image);
// Reads any PNG as RGBA8; throws tacta::InputError naming the file when it cannot.
Image read_png(const std::filesystem::path& file);

// Tolerance of the golden tests: a pixel differs when any channel differs by more than
// `channel_tolerance`; the images match when at most `max_differing_fraction` of pixels differ.
struct CompareTolerance {
  int channel_tolerance = 5;              // of 255
  double max_differing_fraction = 0.001;  // 0.1 %
};

struct ImageComparison {
  bool same_size = false;
  bool matches = false;
  size_t differing_pixels = 0;
  size_t total_pixels = 0;
  int max_channel_difference = 0;  // of 255
  Image difference;                // per-pixel |a - b| amplified, differing pixels in red
  std::string summary() const;
};

ImageComparison compare_images(const Image& actual, const Image& expected,
                               const CompareTolerance& tolerance = {});

// Compares `actual` with the PNG at `golden`. On a mismatch (or a missing golden) writes
// `<out_dir>/<stem>.actual.png` and `<out_dir>/<stem>.diff.png` and returns the comparison with
// matches == false. The summary names the files written.
struct GoldenResult {
  ImageComparison comparison;
  std::filesystem::path actual_file;  // empty when nothing was written
  std::filesystem::path diff_file;
  std::string message;
};
GoldenResult compare_with_golden(const Image& actual, const std::filesystem::path& golden,
                                 const std::filesystem::path& out_dir,
                                 const CompareTolerance& tolerance = {});

}  // namespace tacta::render
