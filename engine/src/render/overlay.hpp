// Screen-space overlay geometry: text lines on a translucent panel (stb_easy_font glyphs) and
// the colour bar of the scalar field. Pixels, origin at the top left.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "tacta/render/frame.hpp"

namespace tacta::render::detail {

struct OverlayVertex {
  std::array<float, 2> position;  // pixels
  std::array<float, 4> colour;    // with alpha
};

// Lines at the top left, at an integer glyph scale; non-ASCII bytes draw as '?'.
void append_text_panel(const std::vector<std::string>& lines, float glyph_scale,
                       std::vector<OverlayVertex>& out);

// A vertical colour bar at the right edge with its range written beside it.
void append_colour_bar(double low, double high, int viewport_width, int viewport_height,
                       float glyph_scale, std::vector<OverlayVertex>& out);

}  // namespace tacta::render::detail
