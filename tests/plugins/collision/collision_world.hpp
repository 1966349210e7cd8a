// Test helpers: small deforming surfaces and a world view over them.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "tacta/collision_api.h"

namespace tacta::testing {

struct TestSurface {
  std::vector<double> start, end, velocities, inverse_masses;
  std::vector<uint32_t> triangles;
  uint32_t vertex_count() const { return static_cast<uint32_t>(start.size() / 3); }
  tacta_collision_surface view(uint32_t body, double thickness) {
    tacta_collision_surface s{};
    s.body_id = body;
    s.vertex_count = vertex_count();
    s.positions_start = start.data();
    s.positions_end = end.data();
    s.velocities = velocities.empty() ? nullptr : velocities.data();
    s.inverse_masses = inverse_masses.empty() ? nullptr : inverse_masses.data();
    s.triangle_count = static_cast<uint32_t>(triangles.size() / 3);
    s.triangles = triangles.data();
    s.thickness = thickness;
    return s;
  }
};

// An n x n grid of squares (2 n^2 triangles) in the plane z = height, side `size` m, centred
// at (cx, cy).
inline TestSurface grid(int n, double size, double cx, double cy, double height) {
  TestSurface s;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      s.start.insert(s.start.end(), {cx + size * (i / double(n) - 0.5),
                                     cy + size * (j / double(n) - 0.5), height});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const uint32_t a = static_cast<uint32_t>(j * (n + 1) + i), b = a + 1,
                     c = a + static_cast<uint32_t>(n + 1), d = c + 1;
      s.triangles.insert(s.triangles.end(), {a, b, d, a, d, c});
    }
  s.end = s.start;
  s.velocities.assign(s.start.size(), 0.0);
  return s;
}

// Moves every vertex by a smooth wave plus noise: `end` from `start`, then start = end next tick.
inline void deform(TestSurface& s, std::mt19937& rng, double amplitude, double phase) {
  std::uniform_real_distribution<double> noise(-amplitude * 0.2, amplitude * 0.2);
  s.start = s.end;
  for (size_t v = 0; v < s.start.size(); v += 3) {
    const double x = s.start[v], y = s.start[v + 1];
    s.end[v] = s.start[v] + noise(rng);
    s.end[v + 1] = s.start[v + 1] + noise(rng);
    s.end[v + 2] = s.start[v + 2] +
                   amplitude * std::sin(3.0 * x + phase) * std::cos(2.0 * y) * 0.3 + noise(rng);
  }
}

}  // namespace tacta::testing
