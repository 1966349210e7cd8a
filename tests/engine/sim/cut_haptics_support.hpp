// Shared by the cutting haptics tests (sim_cut_haptics_test): a soft cube pressed by the simulated
// stylus, blades as planes, and the pieces a separation leaves.
#pragma once

#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "cut_beam_scene.hpp"
#include "sim_test_support.hpp"

namespace tacta::simtest {

// A 0.1 m cube (4 x 4 x 4 cells of 25 mm, x and z in [-50, 50] mm, y in [0, 100] mm) held at its
// bottom face, no gravity (so what moves was moved by the stylus), pressed by sim_stylus following
// `waypoints` (t x y z) with a 4 mm sphere. `stylus_params` and `scene_extra` add YAML lines.
inline std::string cube_scene(const std::string& model, const std::string& waypoints,
                              const std::string& stylus_params = "",
                              const std::string& scene_extra = "") {
  return R"(
name: cut_cube
gravity: [0, 0, 0]
seed: 5
clock: {mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: 0.4}
output: {frames: false, vtk: false}
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [4, 4, 4], origin: [-0.05, 0, -0.05]}}
    material: {youngs_modulus: 2.0e4, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 5.0}
    model: )" +
         model +
         R"(
    fixed: [{box: {min: [-1, -0.001, -1], max: [1, 0.001, 1]}}]
devices:
  - name: stylus
    plugin: sim_stylus
    params:
      workspace_origin: [0, 0.08, 0]
      pattern: waypoints
      waypoints: )" +
         waypoints + "\n" + stylus_params + R"(
    tool: {sphere: {radius: 0.004}}
    coupling: {stiffness: 400, damping: 1.0}
    touches: cube
collision: {broad_phase: bvh}
)" + scene_extra;
}

// From 15 mm above the top face at (x, 0) down to height `bottom_y` (m) over 0.15 s, then held.
inline std::string press_waypoints(double x, double bottom_y) {
  return "[0, " + std::to_string(x) + ", 0.115, 0,   0.15, " + std::to_string(x) + ", " +
         std::to_string(bottom_y) + ", 0]";
}

inline double norm(const double v[3]) { return std::hypot(v[0], v[1], v[2]); }

// The piece (connected through tets) each node belongs to, as a representative node index.
inline std::vector<int> pieces(const VolumeMesh& mesh) {
  std::vector<int> parent(mesh.node_count());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int v) {
    while (parent[static_cast<size_t>(v)] != v)
      v = parent[static_cast<size_t>(v)] =
          parent[static_cast<size_t>(parent[static_cast<size_t>(v)])];
    return v;
  };
  for (size_t t = 0; t < mesh.tet_count(); ++t)
    for (size_t c = 1; c < 4; ++c)
      parent[static_cast<size_t>(root(static_cast<int>(mesh.tets[4 * t + c])))] =
          root(static_cast<int>(mesh.tets[4 * t]));
  for (size_t n = 0; n < parent.size(); ++n) parent[n] = root(static_cast<int>(n));
  return parent;
}

inline size_t node_with_largest_x(const VolumeMesh& mesh) {
  size_t best = 0;
  for (size_t n = 0; n < mesh.node_count(); ++n)
    if (mesh.positions[3 * n] > mesh.positions[3 * best]) best = n;
  return best;
}

}  // namespace tacta::simtest
