#include "scene_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "colour_map.hpp"
#include "tacta/error.hpp"

namespace tacta::render::detail {

namespace {

constexpr int kSphereSlices = 20;  // around the pole axis
constexpr int kSphereStacks = 12;  // pole to pole
constexpr int kArrowSides = 16;

void fail(size_t body_index, const std::string& what) {
  throw InputError({"<render frame>", 0, 0, "bodies[" + std::to_string(body_index) + "]"}, what);
}

void push_triangle(DrawLists& out, const Vec3d& a, const Vec3d& b, const Vec3d& c,
                   const Rgb& colour) {
  const Vec3f n = to_f(normalized(cross(sub(b, a), sub(c, a))));
  out.triangles.push_back({to_f(a), n, colour});
  out.triangles.push_back({to_f(b), n, colour});
  out.triangles.push_back({to_f(c), n, colour});
}

void push_line(DrawLists& out, const Vec3d& a, const Vec3d& b, const Rgb& colour) {
  out.lines.push_back({to_f(a), colour});
  out.lines.push_back({to_f(b), colour});
}

Vec3d vertex(const std::vector<double>& positions, uint32_t i) {
  return {positions[3 * size_t{i}], positions[3 * size_t{i} + 1], positions[3 * size_t{i} + 2]};
}

// Area-weighted vertex normals: the unnormalised face normal carries twice the face's area.
std::vector<Vec3d> vertex_normals(const std::vector<double>& positions,
                                  const std::vector<uint32_t>& triangles) {
  std::vector<Vec3d> normals(positions.size() / 3, Vec3d{0, 0, 0});
  for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
    const Vec3d a = vertex(positions, triangles[t]);
    const Vec3d face = cross(sub(vertex(positions, triangles[t + 1]), a),
                             sub(vertex(positions, triangles[t + 2]), a));
    for (size_t k = 0; k < 3; ++k) normals[triangles[t + k]] = add(normals[triangles[t + k]], face);
  }
  for (Vec3d& n : normals) n = normalized(n);
  return normals;
}

}  // namespace

void append_body(const BodyDraw& body, size_t body_index, double marker_m, DrawLists& out) {
  if (body.positions.size() % 3 != 0)
    fail(body_index,
         "positions must hold 3 values a vertex; found " + std::to_string(body.positions.size()));
  if (body.triangles.size() % 3 != 0)
    fail(body_index,
         "triangles must hold 3 indices each; found " + std::to_string(body.triangles.size()));
  const size_t vertex_count = body.positions.size() / 3;
  for (uint32_t index : body.triangles)
    if (index >= vertex_count)
      fail(body_index, "triangle index " + std::to_string(index) + " is past the " +
                           std::to_string(vertex_count) + " vertices");
  if (!body.scalar.empty() && body.scalar.size() != vertex_count)
    fail(body_index, "scalar must hold one value a vertex (" + std::to_string(vertex_count) +
                         "); found " + std::to_string(body.scalar.size()));
  if (body.fixed_positions.size() % 3 != 0)
    fail(body_index, "fixed_positions must hold 3 values a node");

  const std::vector<Vec3d> normals = vertex_normals(body.positions, body.triangles);
  if (!body.cut_triangles.empty() && body.cut_triangles.size() * 3 != body.triangles.size())
    fail(body_index, "cut_triangles must hold one flag a triangle");
  for (size_t k = 0; k < body.triangles.size(); ++k) {
    const uint32_t index = body.triangles[k];
    const bool cut = !body.cut_triangles.empty() && body.cut_triangles[k / 3] != 0;
    const Rgb colour =
        cut ? body.cut_colour
        : body.scalar.empty()
            ? body.base_colour
            : colour_map(normalise_scalar(body.scalar[index], body.scalar_min, body.scalar_max));
    out.triangles.push_back({to_f(vertex(body.positions, index)), to_f(normals[index]), colour});
  }
  if (body.wireframe) {
    const Rgb edge{0.08f, 0.08f, 0.10f};
    for (size_t t = 0; t + 2 < body.triangles.size(); t += 3)
      for (size_t k = 0; k < 3; ++k) {
        const uint32_t a = body.triangles[t + k];
        const uint32_t b = body.triangles[t + (k + 1) % 3];
        // Shared edges come twice (once each way); the same segment twice draws the same pixels.
        push_line(out, vertex(body.positions, a), vertex(body.positions, b), edge);
      }
  }
  const Rgb fixed_colour{0.15f, 0.15f, 0.18f};
  for (size_t i = 0; i + 2 < body.fixed_positions.size(); i += 3)
    append_cube({body.fixed_positions[i], body.fixed_positions[i + 1], body.fixed_positions[i + 2]},
                marker_m, fixed_colour, out);
}

void append_sphere(const Vec3d& centre, double radius_m, const Rgb& colour, DrawLists& out) {
  auto point = [&](int stack, int slice) {
    const double polar = std::numbers::pi * stack / kSphereStacks;
    const double azimuth = 2 * std::numbers::pi * slice / kSphereSlices;
    const Vec3d n{std::sin(polar) * std::cos(azimuth), std::cos(polar),
                  std::sin(polar) * std::sin(azimuth)};
    return n;
  };
  for (int stack = 0; stack < kSphereStacks; ++stack)
    for (int slice = 0; slice < kSphereSlices; ++slice) {
      const Vec3d n[4] = {point(stack, slice), point(stack + 1, slice), point(stack + 1, slice + 1),
                          point(stack, slice + 1)};
      const int quad[6] = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from outside
      for (int k : quad) {
        const Vec3d& nk = n[k];
        out.triangles.push_back({to_f(add(centre, scaled(nk, radius_m))), to_f(nk), colour});
      }
    }
}

void append_cube(const Vec3d& centre, double half_size_m, const Rgb& colour, DrawLists& out) {
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      Vec3d n{0, 0, 0};
      n[static_cast<size_t>(axis)] = sign;
      const Vec3d u = perpendicular(n);
      const Vec3d v = cross(n, u);
      const Vec3d c = add(centre, scaled(n, half_size_m));
      const Vec3d p[4] = {
          add(c, scaled(add(u, v), -half_size_m)), add(c, scaled(sub(u, v), half_size_m)),
          add(c, scaled(add(u, v), half_size_m)), add(c, scaled(sub(v, u), half_size_m))};
      push_triangle(out, p[0], p[1], p[2], colour);
      push_triangle(out, p[0], p[2], p[3], colour);
    }
}

void append_arrow(const Vec3d& from, const Vec3d& vector, double shaft_radius_m, const Rgb& colour,
                  DrawLists& out) {
  const double total = norm(vector);
  if (!(total > 4 * shaft_radius_m)) return;
  const Vec3d axis = scaled(vector, 1.0 / total);
  const Vec3d u = perpendicular(axis);
  const Vec3d v = cross(axis, u);
  const double head_length = std::min(0.3 * total, 8 * shaft_radius_m);
  const double head_radius = 2.5 * shaft_radius_m;
  const Vec3d neck = add(from, scaled(axis, total - head_length));
  const Vec3d tip = add(from, vector);
  auto ring = [&](int side) {
    const double a = 2 * std::numbers::pi * side / kArrowSides;
    return add(scaled(u, std::cos(a)), scaled(v, std::sin(a)));
  };
  for (int side = 0; side < kArrowSides; ++side) {
    const Vec3d r0 = ring(side);
    const Vec3d r1 = ring(side + 1);
    // Shaft: two triangles with radial normals.
    const Vec3d a0 = add(from, scaled(r0, shaft_radius_m)),
                a1 = add(from, scaled(r1, shaft_radius_m));
    const Vec3d b0 = add(neck, scaled(r0, shaft_radius_m)),
                b1 = add(neck, scaled(r1, shaft_radius_m));
    out.triangles.push_back({to_f(a0), to_f(r0), colour});
    out.triangles.push_back({to_f(a1), to_f(r1), colour});
    out.triangles.push_back({to_f(b1), to_f(r1), colour});
    out.triangles.push_back({to_f(a0), to_f(r0), colour});
    out.triangles.push_back({to_f(b1), to_f(r1), colour});
    out.triangles.push_back({to_f(b0), to_f(r0), colour});
    // Head: cone side and its base disc.
    const Vec3d h0 = add(neck, scaled(r0, head_radius)), h1 = add(neck, scaled(r1, head_radius));
    push_triangle(out, h0, h1, tip, colour);
    push_triangle(out, neck, h1, h0, colour);
  }
}

void append_tool(const ToolDraw& tool, const Rgb& colour, DrawLists& out) {
  if (!tool.present) return;
  if (!tool.mesh || tool.mesh->triangle_count() == 0) {
    append_sphere(tool.position, tool.radius, colour, out);
    return;
  }
  const SurfaceMesh& mesh = *tool.mesh;
  std::vector<double> world(mesh.positions.size());
  const std::array<double, 4> q = unit_quaternion(tool.orientation);
  for (size_t i = 0; i + 2 < mesh.positions.size(); i += 3) {
    const Vec3d p =
        add(tool.position,
            rotate(q, {mesh.positions[i], mesh.positions[i + 1], mesh.positions[i + 2]}));
    world[i] = p[0];
    world[i + 1] = p[1];
    world[i + 2] = p[2];
  }
  BodyDraw as_body;
  as_body.positions = std::move(world);
  as_body.triangles = mesh.triangles;
  as_body.base_colour = colour;
  append_body(as_body, 0, 0, out);
}

void append_floor_grid(double height_m, const Bounds& bounds, DrawLists& out) {
  const double extent =
      std::max({bounds.max[0] - bounds.min[0], bounds.max[2] - bounds.min[2], 1e-3});
  const double spacing = std::pow(10.0, std::floor(std::log10(extent)));
  const double margin = 2 * spacing;
  const double x0 = std::floor((bounds.min[0] - margin) / spacing) * spacing;
  const double x1 = std::ceil((bounds.max[0] + margin) / spacing) * spacing;
  const double z0 = std::floor((bounds.min[2] - margin) / spacing) * spacing;
  const double z1 = std::ceil((bounds.max[2] + margin) / spacing) * spacing;
  const Rgb colour{0.38f, 0.39f, 0.42f};
  const int nx = static_cast<int>(std::lround((x1 - x0) / spacing));
  const int nz = static_cast<int>(std::lround((z1 - z0) / spacing));
  for (int i = 0; i <= nx; ++i) {
    const double x = x0 + i * spacing;
    push_line(out, {x, height_m, z0}, {x, height_m, z1}, colour);
  }
  for (int i = 0; i <= nz; ++i) {
    const double z = z0 + i * spacing;
    push_line(out, {x0, height_m, z}, {x1, height_m, z}, colour);
  }
}

void append_axes(double length_m, DrawLists& out) {
  push_line(out, {0, 0, 0}, {length_m, 0, 0}, {0.90f, 0.25f, 0.25f});
  push_line(out, {0, 0, 0}, {0, length_m, 0}, {0.30f, 0.85f, 0.30f});
  push_line(out, {0, 0, 0}, {0, 0, length_m}, {0.30f, 0.45f, 0.95f});
}

}  // namespace tacta::render::detail
