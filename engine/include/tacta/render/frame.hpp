// What the renderer draws: a plain description of one frame, filled by the render task from a
// published snapshot (or by hand in tests). Plain vectors of doubles so that filling it needs no
// knowledge of GL. Units: metres, newtons, seconds; the world's up axis is +y (gravity is -y).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "tacta/mesh.hpp"

namespace tacta::render {

using Vec3d = std::array<double, 3>;
using Rgb = std::array<float, 3>;  // display (sRGB) values, 0..1

struct Camera {
  Vec3d eye{0.3, 0.25, 0.45};  // m
  Vec3d target{0, 0, 0};       // m
  Vec3d up{0, 1, 0};
  double vertical_fov_rad = 0.7;  // about 40 degrees
};

struct BodyDraw {
  std::vector<double> positions;    // 3 per vertex, m (current, deformed)
  std::vector<uint32_t> triangles;  // 3 per triangle, counter-clockwise seen from outside
  // Optional per-vertex scalar (e.g. displacement magnitude in m, or von Mises stress in Pa),
  // coloured through the colour map over [scalar_min, scalar_max]; empty: base_colour.
  std::vector<double> scalar;
  double scalar_min = 0;
  double scalar_max = 1;
  Rgb base_colour{0.80f, 0.55f, 0.45f};
  // Per triangle: 1 when a cut exposed it, drawn in cut_colour (the wound, not the skin); empty:
  // none.
  std::vector<uint8_t> cut_triangles;
  Rgb cut_colour{0.55f, 0.08f, 0.10f};
  bool wireframe = false;               // draw the triangle edges on top
  std::vector<double> fixed_positions;  // 3 per fixed node, m: drawn as small dark cubes
};

struct ToolDraw {
  bool present = false;
  Vec3d position{0, 0, 0};                        // m, the tool's origin (tip) in the world
  std::array<double, 4> orientation{1, 0, 0, 0};  // unit quaternion w, x, y, z (tool to world)
  double radius = 0.005;                          // m, sphere fallback when no mesh is given
  std::optional<SurfaceMesh> mesh;                // tool shape in the tool's frame, m
};

struct ContactDraw {
  Vec3d point{0, 0, 0};   // m
  Vec3d normal{0, 1, 0};  // unit, pointing out of the touched surface
};

struct RenderFrame {
  Camera camera;
  std::vector<BodyDraw> bodies;
  ToolDraw tool;
  std::optional<Vec3d> proxy;  // m, the proxy (god-object) position on the surface
  std::vector<ContactDraw> contacts;
  Vec3d force{0, 0, 0};  // N, force rendered to the device, drawn as an arrow at the tool
  double force_arrow_scale = 0.01;           // m/N: arrow length per newton
  std::optional<double> floor_height = 0.0;  // m along +y; nullopt: no floor grid
  bool axes = true;                          // x red, y green, z blue at the origin
  std::vector<std::string> overlay_lines;    // top-left text, one entry a line (ASCII)
  Rgb background{0.16f, 0.17f, 0.20f};
};

// Axis-aligned bounds of everything drawn (bodies, tool, proxy); empty frame gives a unit box.
struct Bounds {
  Vec3d min{0, 0, 0};
  Vec3d max{0, 0, 0};
};
Bounds frame_bounds(const RenderFrame& frame);

// Places the camera so the frame's bounds fill the view, looking from `view_direction`
// (from target to eye; need not be unit) with +y up; keeps the field of view.
void fit_camera(RenderFrame& frame, const Vec3d& view_direction = {0.55, 0.45, 0.9});

}  // namespace tacta::render
