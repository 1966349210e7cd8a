#include "overlay.hpp"

#include <algorithm>
#include <cstdio>

#include "colour_map.hpp"

// stb_easy_font is a single header of static functions: only this file includes it.
#include <stb/stb_easy_font.h>

namespace tacta::render::detail {

namespace {

constexpr float kMargin = 8;            // pixels from the viewport edge
constexpr float kLineHeight = 11;       // glyph pixels a line, before scaling
constexpr float kPanelPadding = 6;      // pixels around the text
constexpr size_t kStbVertexBytes = 16;  // x, y, z floats and 4 colour bytes

void push_quad(std::vector<OverlayVertex>& out, float x0, float y0, float x1, float y1,
               const std::array<float, 4>& c0, const std::array<float, 4>& c1) {
  // c0 along the top edge, c1 along the bottom: a vertical gradient when they differ.
  out.push_back({{x0, y0}, c0});
  out.push_back({{x1, y0}, c0});
  out.push_back({{x1, y1}, c1});
  out.push_back({{x0, y0}, c0});
  out.push_back({{x1, y1}, c1});
  out.push_back({{x0, y1}, c1});
}

std::string printable(const std::string& line) {
  std::string s = line;
  for (char& c : s)
    if (c < 32 || c > 126) c = '?';
  return s;
}

float text_width(const std::string& line) {
  std::string s = printable(line);
  return static_cast<float>(stb_easy_font_width(s.data()));
}

// Appends the glyph quads of one line at (x, y) top-left, in pixels.
void append_line(const std::string& line, float x, float y, float glyph_scale,
                 const std::array<float, 4>& colour, std::vector<OverlayVertex>& out) {
  std::string s = printable(line);
  std::vector<char> buffer(s.size() * 270 * 4 + 64);  // worst case well above stb's per-char use
  unsigned char unused_colour[4] = {255, 255, 255, 255};
  const int quads = stb_easy_font_print(0, 0, s.data(), unused_colour, buffer.data(),
                                        static_cast<int>(buffer.size()));
  for (int q = 0; q < quads; ++q) {
    float corner[4][2];
    for (int k = 0; k < 4; ++k) {
      float xy[2];
      std::copy_n(
          buffer.data() + (static_cast<size_t>(q) * 4 + static_cast<size_t>(k)) * kStbVertexBytes,
          sizeof xy, reinterpret_cast<char*>(xy));
      corner[k][0] = x + xy[0] * glyph_scale;
      corner[k][1] = y + xy[1] * glyph_scale;
    }
    push_quad(out, corner[0][0], corner[0][1], corner[2][0], corner[2][1], colour, colour);
  }
}

}  // namespace

void append_text_panel(const std::vector<std::string>& lines, float glyph_scale,
                       std::vector<OverlayVertex>& out) {
  if (lines.empty()) return;
  float widest = 0;
  for (const std::string& line : lines) widest = std::max(widest, text_width(line));
  const float line_step = kLineHeight * glyph_scale;
  const float x1 = kMargin + 2 * kPanelPadding + widest * glyph_scale;
  const float y1 =
      kMargin + 2 * kPanelPadding + line_step * static_cast<float>(lines.size()) - 3 * glyph_scale;
  push_quad(out, kMargin, kMargin, x1, y1, {0, 0, 0, 0.55f}, {0, 0, 0, 0.55f});
  const std::array<float, 4> ink{0.95f, 0.95f, 0.92f, 1};
  for (size_t i = 0; i < lines.size(); ++i)
    append_line(lines[i], kMargin + kPanelPadding,
                kMargin + kPanelPadding + line_step * static_cast<float>(i), glyph_scale, ink, out);
}

void append_colour_bar(double low, double high, int viewport_width, int viewport_height,
                       float glyph_scale, std::vector<OverlayVertex>& out) {
  char low_text[32];
  char high_text[32];
  std::snprintf(low_text, sizeof low_text, "%.3g", low);
  std::snprintf(high_text, sizeof high_text, "%.3g", high);
  const float label_width = std::max(text_width(low_text), text_width(high_text)) * glyph_scale;
  const float bar_width = 14;
  const float height = std::min(220.0f, 0.5f * static_cast<float>(viewport_height));
  const float x1 = static_cast<float>(viewport_width) - kMargin - label_width - 6;
  const float x0 = x1 - bar_width;
  const float y0 = kMargin + 4;
  constexpr int kSteps = 32;  // gradient bands, top = high
  for (int i = 0; i < kSteps; ++i) {
    const float ya = y0 + height * static_cast<float>(i) / kSteps;
    const float yb = y0 + height * static_cast<float>(i + 1) / kSteps;
    const Rgb top = colour_map(1.0 - static_cast<double>(i) / kSteps);
    const Rgb bottom = colour_map(1.0 - static_cast<double>(i + 1) / kSteps);
    push_quad(out, x0, ya, x1, yb, {top[0], top[1], top[2], 1},
              {bottom[0], bottom[1], bottom[2], 1});
  }
  const std::array<float, 4> ink{0.95f, 0.95f, 0.92f, 1};
  append_line(high_text, x1 + 6, y0, glyph_scale, ink, out);
  append_line(low_text, x1 + 6, y0 + height - 7 * glyph_scale, glyph_scale, ink, out);
}

}  // namespace tacta::render::detail
