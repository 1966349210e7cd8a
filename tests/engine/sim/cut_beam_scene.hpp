// The clamped beam the cutting tests cut, the plane blades they cut with, a scalpel device that
// sweeps a blade through it, and the pieces a cut mesh is in.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "tacta/mesh.hpp"

namespace tacta::simtest {

// A 0.1 x 0.02 x 0.02 m beam along x, 10 x 2 x 2 cells, clamped at x = 0, gravity along -z and
// no mass-proportional damping (that would slow a free piece's fall: -alpha M v is no internal
// force).
inline std::string beam_scene(const std::string& model, const std::string& extra = "") {
  return R"(
name: cut_beam
gravity: [0, 0, -9.81]
clock: {duration_s: 0.2}
output: {frames: false, vtk: false}
bodies:
  - name: beam
    mesh: {beam_grid: {size: [0.1, 0.02, 0.02], cells: [10, 2, 2]}}
    material: {youngs_modulus: 1.0e5, poisson_ratio: 0.3, density: 1000, rayleigh_mass: 0}
    model: )" +
         model + R"(
    fixed: [{box: {min: [-1, -1, -1], max: [0.0001, 1, 1]}}]
)" + extra;
}

// Two triangles covering the plane x = `x` from y0 to y1 (m), z well past the bodies cut.
inline std::vector<double> quad_x(double x, double y0, double y1) {
  return {x, y0, -1, x, y1, -1, x, y1, 1,  //
          x, y0, -1, x, y1, 1,  x, y0, 1};
}
// The plane x = `x`, well past the bodies cut.
inline std::vector<double> plane_x(double x) { return quad_x(x, -1, 1); }

// Body keys for beam_scene's `extra`: the nodes of the cell face x = 0.05 slide in x and z only
// (y held at rest), and the tip face x = 0.1 is lifted 5 mm along z over 0.2 s.
inline const char* const kPrescribedBeam = R"(
    prescribed:
      - region: {box: {min: [0.0499, -1, -1], max: [0.0501, 1, 1]}}
        axes: [y]
        displacement: [0, 0, 0]
      - region: {box: {min: [0.0999, -1, -1], max: [1, 1, 1]}}
        displacement: {ramp: {to: [0, 0, 0.005], duration_s: 0.2}}
)";

// A scalpel from a device: sim_stylus holds button 0 from 0.04 to 0.17 s while its hand sweeps a
// vertical blade along y through the beam at x = 0.05 (a cell face: the cut parts the beam
// there). The coupling is soft so the hand passes through the beam as a surgeon's would.
inline const char* const kScalpelDevice = R"(
devices:
  - name: scalpel
    plugin: sim_stylus
    params:
      workspace_origin: [0.05, 0.01, 0.05]
      limit_to_workspace: false
      waypoints: [0, 0.05, -0.02, 0.03,  0.05, 0.05, -0.02, 0.03,  0.15, 0.05, 0.045, 0.03]
      button_times: [0.04, 0.17]
    tool: {sphere: {radius: 0.001}, blade: {edge: [[0, 0, 0], [0, 0, -0.1]], button: 0}}
    coupling: {stiffness: 5, damping: 0.01}
    touches: beam
)";

// The pieces of a mesh: per node, the lowest node joined to it through tets; and the nodes at the
// beam's two ends (smallest and largest rest x).
struct Pieces {
  std::vector<uint32_t> piece;
  uint32_t clamp = 0, tip = 0;
  explicit Pieces(const VolumeMesh& mesh) : piece(mesh.node_count()) {
    std::iota(piece.begin(), piece.end(), 0u);
    auto root = [&](uint32_t v) {
      while (piece[v] != v) v = piece[v] = piece[piece[v]];
      return v;
    };
    for (size_t t = 0; t < mesh.tet_count(); ++t)
      for (int c = 1; c < 4; ++c) {
        const uint32_t a = root(mesh.tets[4 * t + c]), b = root(mesh.tets[4 * t]);
        piece[std::max(a, b)] = std::min(a, b);
      }
    for (uint32_t n = 0; n < mesh.node_count(); ++n) {
      piece[n] = root(n);
      if (mesh.positions[3 * n] > mesh.positions[3 * tip]) tip = n;
      if (mesh.positions[3 * n] < mesh.positions[3 * clamp]) clamp = n;
    }
  }
  bool in_two() const { return piece[tip] != piece[clamp]; }
};

}  // namespace tacta::simtest
