#include "colour_map.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tacta::render::detail {

namespace {
// Anchor colours at t = 0, 1/8, ..., 1: the published key values of matplotlib's viridis map
// (#440154 #482878 #3E4A89 #31688E #26828E #1F9E89 #35B779 #6DCD59 #FDE725), linearly
// interpolated between anchors.
constexpr std::array<std::array<int, 3>, 9> kAnchors{{{0x44, 0x01, 0x54},
                                                      {0x48, 0x28, 0x78},
                                                      {0x3E, 0x4A, 0x89},
                                                      {0x31, 0x68, 0x8E},
                                                      {0x26, 0x82, 0x8E},
                                                      {0x1F, 0x9E, 0x89},
                                                      {0x35, 0xB7, 0x79},
                                                      {0x6D, 0xCD, 0x59},
                                                      {0xFD, 0xE7, 0x25}}};
}  // namespace

Rgb colour_map(double t) {
  if (!(t > 0)) t = 0;  // also catches NaN
  if (t > 1) t = 1;
  const double scaled = t * static_cast<double>(kAnchors.size() - 1);
  const size_t low = std::min(static_cast<size_t>(scaled), kAnchors.size() - 2);
  const double w = scaled - static_cast<double>(low);
  Rgb out{};
  for (size_t c = 0; c < 3; ++c) {
    const double a = kAnchors[low][c] / 255.0;
    const double b = kAnchors[low + 1][c] / 255.0;
    out[c] = static_cast<float>(a + (b - a) * w);
  }
  return out;
}

double normalise_scalar(double value, double low, double high) {
  const double span = high - low;
  if (!(span > 0)) return 0;
  return (value - low) / span;
}

}  // namespace tacta::render::detail
