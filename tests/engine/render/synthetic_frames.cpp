#include "synthetic_frames.hpp"

#include <cmath>
#include <numbers>

namespace tacta::render::testing {

namespace {

// Appends a (a+1) x (b+1) vertex grid on the plane through `origin` spanned by edge_u, edge_v.
void append_face(BodyDraw& body, const Vec3d& origin, const Vec3d& edge_u, const Vec3d& edge_v,
                 int a, int b) {
  const uint32_t first = static_cast<uint32_t>(body.positions.size() / 3);
  for (int j = 0; j <= b; ++j)
    for (int i = 0; i <= a; ++i)
      for (size_t k = 0; k < 3; ++k)
        body.positions.push_back(origin[k] + edge_u[k] * i / a + edge_v[k] * j / b);
  auto at = [&](int i, int j) { return first + static_cast<uint32_t>(j * (a + 1) + i); };
  for (int j = 0; j < b; ++j)
    for (int i = 0; i < a; ++i) {
      body.triangles.insert(body.triangles.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      body.triangles.insert(body.triangles.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
}

}  // namespace

BodyDraw box_surface(int nx, int ny, int nz, const Vec3d& size) {
  BodyDraw body;
  const double x = size[0], y = size[1], z = size[2];
  // Each face's edge_u x edge_v points outward.
  append_face(body, {0, 0, 0}, {0, 0, z}, {0, y, 0}, nz, ny);  // x = 0, normal -x
  append_face(body, {x, 0, 0}, {0, y, 0}, {0, 0, z}, ny, nz);  // x = X, normal +x
  append_face(body, {0, 0, 0}, {x, 0, 0}, {0, 0, z}, nx, nz);  // y = 0, normal -y
  append_face(body, {0, y, 0}, {0, 0, z}, {x, 0, 0}, nz, nx);  // y = Y, normal +y
  append_face(body, {0, 0, 0}, {0, y, 0}, {x, 0, 0}, ny, nx);  // z = 0, normal -z
  append_face(body, {0, 0, z}, {x, 0, 0}, {0, y, 0}, nx, ny);  // z = Z, normal +z
  return body;
}

BodyDraw sphere_surface(const Vec3d& centre, double radius, int slices, int stacks) {
  BodyDraw body;
  for (int j = 0; j <= stacks; ++j)
    for (int i = 0; i <= slices; ++i) {
      const double polar = std::numbers::pi * j / stacks;
      const double azimuth = 2 * std::numbers::pi * i / slices;
      body.positions.push_back(centre[0] + radius * std::sin(polar) * std::cos(azimuth));
      body.positions.push_back(centre[1] + radius * std::cos(polar));
      body.positions.push_back(centre[2] + radius * std::sin(polar) * std::sin(azimuth));
    }
  auto at = [&](int i, int j) { return static_cast<uint32_t>(j * (slices + 1) + i); };
  for (int j = 0; j < stacks; ++j)
    for (int i = 0; i < slices; ++i) {
      body.triangles.insert(body.triangles.end(), {at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      body.triangles.insert(body.triangles.end(), {at(i, j), at(i + 1, j), at(i + 1, j + 1)});
    }
  return body;
}

namespace {

RenderFrame bent_cantilever() {
  // Beam 0.20 m x 0.04 m x 0.04 m clamped at x = 0; tip deflection 0.03 m down with the static
  // Euler-Bernoulli shape v(x) = d (x/L)^2 (3 - x/L) / 2 under an end load.
  const double length = 0.20, tip_deflection = 0.03;
  RenderFrame frame;
  BodyDraw beam = box_surface(10, 2, 2, {length, 0.04, 0.04});
  beam.wireframe = true;
  beam.scalar.resize(beam.positions.size() / 3);
  for (size_t v = 0; v < beam.scalar.size(); ++v) {
    const double s = beam.positions[3 * v] / length;
    const double deflection = tip_deflection * s * s * (3 - s) / 2;
    beam.positions[3 * v + 1] += 0.05 - deflection;
    beam.scalar[v] = deflection;
    if (beam.positions[3 * v] == 0)
      beam.fixed_positions.insert(
          beam.fixed_positions.end(),
          {beam.positions[3 * v], beam.positions[3 * v + 1], beam.positions[3 * v + 2]});
  }
  beam.scalar_min = 0;
  beam.scalar_max = tip_deflection;
  frame.bodies.push_back(std::move(beam));
  frame.floor_height = 0.0;
  fit_camera(frame);
  return frame;
}

RenderFrame coloured_sphere() {
  RenderFrame frame;
  BodyDraw ball = sphere_surface({0, 0.06, 0}, 0.05, 32, 16);
  for (size_t v = 0; v < ball.positions.size() / 3; ++v)
    ball.scalar.push_back(ball.positions[3 * v + 1]);
  ball.scalar_min = 0.01;
  ball.scalar_max = 0.11;
  frame.bodies.push_back(std::move(ball));
  frame.overlay_lines = {"sphere, colour = height (m)"};
  fit_camera(frame, {0.3, 0.35, 1.0});
  return frame;
}

// A stylus-like tool mesh: a cone tip at the origin and a cylinder along +y, m.
SurfaceMesh stylus_like() {
  SurfaceMesh mesh;
  const int sides = 12;
  const double radius = 0.004, tip = 0.012, total = 0.08;
  mesh.positions = {0, 0, 0};
  for (double y : {tip, total})
    for (int i = 0; i < sides; ++i) {
      const double a = 2 * std::numbers::pi * i / sides;
      mesh.positions.insert(mesh.positions.end(), {radius * std::cos(a), y, radius * std::sin(a)});
    }
  mesh.positions.insert(mesh.positions.end(), {0, total, 0});
  const uint32_t top = static_cast<uint32_t>(2 * sides + 1);
  for (uint32_t i = 0; i < static_cast<uint32_t>(sides); ++i) {
    const uint32_t n = (i + 1) % sides;
    mesh.triangles.insert(mesh.triangles.end(), {0, 1 + i, 1 + n});              // cone
    mesh.triangles.insert(mesh.triangles.end(), {1 + i, 1 + sides + n, 1 + n});  // side
    mesh.triangles.insert(mesh.triangles.end(), {1 + i, 1 + sides + i, 1 + sides + n});
    mesh.triangles.insert(mesh.triangles.end(), {top, 1 + sides + n, 1 + sides + i});  // cap
  }
  return mesh;
}

RenderFrame tool_on_plate() {
  RenderFrame frame;
  // Plate 0.12 m square at y = 0.02 m, dented by a Gaussian of depth 6 mm under the tool.
  BodyDraw plate = box_surface(12, 1, 12, {0.12, 0.02, 0.12});
  const double cx = 0.06, cz = 0.06, depth = 0.006, width = 0.015;
  for (size_t v = 0; v < plate.positions.size() / 3; ++v) {
    double& y = plate.positions[3 * v + 1];
    if (y > 0.019) {
      const double dx = plate.positions[3 * v] - cx, dz = plate.positions[3 * v + 2] - cz;
      y -= depth * std::exp(-(dx * dx + dz * dz) / (2 * width * width));
    }
  }
  plate.base_colour = {0.85f, 0.52f, 0.50f};
  frame.bodies.push_back(std::move(plate));
  frame.tool.present = true;
  frame.tool.position = {cx, 0.02 - depth + 0.001, cz};
  frame.tool.mesh = stylus_like();
  const double tilt = 0.35;  // rad about z
  frame.tool.orientation = {std::cos(tilt / 2), 0, 0, std::sin(tilt / 2)};
  frame.proxy = Vec3d{cx, 0.02 - depth, cz};
  frame.contacts = {{{cx, 0.02 - depth, cz}, {0, 1, 0}},
                    {{cx + 0.004, 0.02 - depth + 0.0005, cz}, {-0.1, 1, 0}}};
  frame.force = {1.4, 2.1, 0.6};    // N
  frame.force_arrow_scale = 0.012;  // m/N
  frame.overlay_lines = {"t = 1.250 s", "model: tensor_mass", "force: 2.59 N", "tick p99: 0.41 ms"};
  fit_camera(frame, {0.8, 0.6, 1.0});
  return frame;
}

RenderFrame top_view() {
  RenderFrame frame;
  frame.bodies.push_back(box_surface(4, 4, 4, {0.05, 0.05, 0.05}));
  frame.bodies.back().base_colour = {0.45f, 0.65f, 0.85f};
  frame.tool.present = true;
  frame.tool.position = {0.025, 0.07, 0.025};
  frame.tool.radius = 0.006;
  frame.axes = true;
  fit_camera(frame, {0, 1, 0});
  return frame;
}

}  // namespace

std::vector<NamedFrame> golden_frames() {
  return {{"bent_cantilever", bent_cantilever()},
          {"coloured_sphere", coloured_sphere()},
          {"tool_on_plate", tool_on_plate()},
          {"top_view_sphere_tool", top_view()}};
}

}  // namespace tacta::render::testing
