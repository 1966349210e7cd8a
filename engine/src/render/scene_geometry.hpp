// CPU-side geometry of a frame: lit triangles and unlit lines in world space, in floats, ready
// to upload. Built fresh for every frame (bodies deform), so nothing here caches.
#pragma once

#include <vector>

#include "math.hpp"
#include "tacta/render/frame.hpp"

namespace tacta::render::detail {

struct LitVertex {
  Vec3f position;  // m
  Vec3f normal;    // unit
  Vec3f colour;
};

struct LineVertex {
  Vec3f position;  // m
  Vec3f colour;
};

struct DrawLists {
  std::vector<LitVertex> triangles;  // 3 a triangle
  std::vector<LineVertex> lines;     // 2 a segment
  void clear() {
    triangles.clear();
    lines.clear();
  }
};

// Smooth-shaded body (area-weighted vertex normals of the current shape), its wireframe and its
// fixed nodes (cubes of half-size marker_m). Throws tacta::InputError on inconsistent arrays.
void append_body(const BodyDraw& body, size_t body_index, double marker_m, DrawLists& out);

void append_sphere(const Vec3d& centre, double radius_m, const Rgb& colour, DrawLists& out);
void append_cube(const Vec3d& centre, double half_size_m, const Rgb& colour, DrawLists& out);

// Cylinder shaft plus cone head from `from` along `vector` (m); nothing when it is too short.
void append_arrow(const Vec3d& from, const Vec3d& vector, double shaft_radius_m, const Rgb& colour,
                  DrawLists& out);

// The tool's mesh placed at its pose, or a sphere of its radius when it has none.
void append_tool(const ToolDraw& tool, const Rgb& colour, DrawLists& out);

// Grid of lines on the plane y = height covering the xz footprint of `bounds`, spacing chosen as
// a power of ten so that about ten lines cross it.
void append_floor_grid(double height_m, const Bounds& bounds, DrawLists& out);
void append_axes(double length_m, DrawLists& out);

}  // namespace tacta::render::detail
