#include "demo_frame.hpp"

#include <cmath>
#include <numbers>

namespace tacta::view {

namespace {

constexpr int kCells = 24;            // plate grid cells a side
constexpr double kSize = 0.12;        // m, plate side
constexpr double kDentWidth = 0.015;  // m, Gaussian width of the dent
constexpr double kMaxDepth = 0.008;   // m
constexpr double kStiffness = 400;    // N/m, the force per metre of dent drawn as the arrow

}  // namespace

render::RenderFrame demo_frame(double time_s, bool wireframe, DemoState& state) {
  render::RenderFrame frame;
  render::BodyDraw plate;
  state.depth_m = kMaxDepth * 0.5 * (1 - std::cos(2 * std::numbers::pi * time_s));
  state.force_N = kStiffness * state.depth_m;
  const double centre = kSize / 2;
  for (int j = 0; j <= kCells; ++j)
    for (int i = 0; i <= kCells; ++i) {
      const double x = kSize * i / kCells, z = kSize * j / kCells;
      const double r2 = (x - centre) * (x - centre) + (z - centre) * (z - centre);
      const double dent = state.depth_m * std::exp(-r2 / (2 * kDentWidth * kDentWidth));
      plate.positions.insert(plate.positions.end(), {x, 0.02 - dent, z});
      plate.scalar.push_back(dent);
    }
  for (int j = 0; j < kCells; ++j)
    for (int i = 0; i < kCells; ++i) {
      const auto at = [&](int a, int b) { return static_cast<uint32_t>(b * (kCells + 1) + a); };
      plate.triangles.insert(plate.triangles.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1)});
      plate.triangles.insert(plate.triangles.end(), {at(i, j), at(i + 1, j + 1), at(i + 1, j)});
    }
  plate.scalar_max = kMaxDepth;
  plate.wireframe = wireframe;
  frame.bodies.push_back(std::move(plate));
  frame.tool.present = true;
  frame.tool.position = {centre, 0.02 - state.depth_m, centre};
  frame.tool.radius = 0.004;
  frame.proxy = frame.tool.position;
  frame.force = {0, state.force_N, 0};
  frame.force_arrow_scale = 0.01;  // m/N
  render::fit_camera(frame, {0.8, 0.7, 1.0});
  return frame;
}

}  // namespace tacta::view
