// Test helper: a soft block as an explicit mass-spring lattice (symplectic Euler), its closed
// outward surface for collision, and an inside test (generalised winding number).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "tacta/collision_api.h"

namespace tacta::testing {

struct SoftBlock {
  int cells = 2;                               // per side
  std::vector<double> start, end, velocities;  // 3 per vertex: m, m, m/s
  std::vector<double> masses, inverse_masses;  // kg, 1/kg
  std::vector<uint32_t> triangles;             // outward, counter-clockwise
  std::vector<std::array<uint32_t, 2>> springs;
  std::vector<double> rest_lengths;  // m
  // Explicit integration at 1 ms is stable for these with 2-4 cells and 0.1-0.5 kg.
  double stiffness = 200;  // N/m per spring
  double damping = 0.05;   // N s/m per spring, along it

  uint32_t vertex_count() const { return static_cast<uint32_t>(start.size() / 3); }
  uint32_t index(int i, int j, int k) const {
    return static_cast<uint32_t>((k * (cells + 1) + j) * (cells + 1) + i);
  }

  // A cube of side `size` (m) with its lowest corner at `corner`, total mass (kg).
  static SoftBlock make(int cells, double size, std::array<double, 3> corner, double total_mass) {
    SoftBlock b;
    b.cells = cells;
    const int n = cells + 1;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i)
          b.start.insert(b.start.end(), {corner[0] + size * i / cells, corner[1] + size * j / cells,
                                         corner[2] + size * k / cells});
    b.end = b.start;
    b.velocities.assign(b.start.size(), 0.0);
    b.masses.assign(b.vertex_count(), total_mass / b.vertex_count());
    b.inverse_masses.assign(b.vertex_count(), b.vertex_count() / total_mass);
    b.add_surface();
    for (int k = 0; k < cells; ++k)
      for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
          uint32_t corners[8];
          for (int c = 0; c < 8; ++c)
            corners[c] = b.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
          for (int p = 0; p < 8; ++p)
            for (int q = p + 1; q < 8; ++q) {
              b.springs.push_back({corners[p], corners[q]});
              b.rest_lengths.push_back(b.distance(corners[p], corners[q]));
            }
        }
    return b;
  }

  double distance(uint32_t p, uint32_t q) const {
    double s = 0;
    for (int a = 0; a < 3; ++a)
      s += (end[3 * p + a] - end[3 * q + a]) * (end[3 * p + a] - end[3 * q + a]);
    return std::sqrt(s);
  }

  // The tick's proposed motion: start = accepted end of the last tick, then symplectic Euler.
  void integrate(double dt, const std::array<double, 3>& gravity) {
    start = end;
    std::vector<double> force(start.size(), 0.0);
    for (size_t s = 0; s < springs.size(); ++s) {
      const uint32_t p = springs[s][0], q = springs[s][1];
      double d[3], dv[3], length = distance(p, q);
      for (int a = 0; a < 3; ++a) {
        d[a] = (end[3 * q + a] - end[3 * p + a]) / (length > 0 ? length : 1);
        dv[a] = velocities[3 * q + a] - velocities[3 * p + a];
      }
      const double magnitude = stiffness * (length - rest_lengths[s]) +
                               damping * (dv[0] * d[0] + dv[1] * d[1] + dv[2] * d[2]);
      for (int a = 0; a < 3; ++a) {
        force[3 * p + a] += magnitude * d[a];
        force[3 * q + a] -= magnitude * d[a];
      }
    }
    for (uint32_t v = 0; v < vertex_count(); ++v)
      for (int a = 0; a < 3; ++a) {
        if (inverse_masses[v] > 0)
          velocities[3 * v + a] += dt * (force[3 * v + a] * inverse_masses[v] + gravity[a]);
        end[3 * v + a] = start[3 * v + a] + dt * velocities[3 * v + a];
      }
  }

  tacta_collision_surface view(uint32_t body, double thickness) {
    tacta_collision_surface s{};
    s.body_id = body;
    s.vertex_count = vertex_count();
    s.positions_start = start.data();
    s.positions_end = end.data();
    s.velocities = velocities.data();
    s.inverse_masses = inverse_masses.data();
    s.triangle_count = static_cast<uint32_t>(triangles.size() / 3);
    s.triangles = triangles.data();
    s.thickness = thickness;
    return s;
  }

  std::array<double, 3> momentum() const {
    std::array<double, 3> p{0, 0, 0};
    for (uint32_t v = 0; v < vertex_count(); ++v)
      for (int a = 0; a < 3; ++a) p[static_cast<size_t>(a)] += masses[v] * velocities[3 * v + a];
    return p;
  }
  double kinetic_energy() const {  // J
    double e = 0;
    for (uint32_t v = 0; v < vertex_count(); ++v)
      for (int a = 0; a < 3; ++a)
        e += 0.5 * masses[v] * velocities[3 * v + a] * velocities[3 * v + a];
    return e;
  }
  std::array<double, 3> first_moment() const {  // sum m x (kg m), over end positions
    std::array<double, 3> p{0, 0, 0};
    for (uint32_t v = 0; v < vertex_count(); ++v)
      for (int a = 0; a < 3; ++a) p[static_cast<size_t>(a)] += masses[v] * end[3 * v + a];
    return p;
  }

  // Generalised winding number of the closed surface (end positions) about x: ~1 inside.
  double winding(const double* x) const {
    double total = 0;
    for (size_t t = 0; t < triangles.size(); t += 3) {
      double r[3][3], len[3];
      for (int c = 0; c < 3; ++c) {
        for (int a = 0; a < 3; ++a)
          r[c][a] = end[3 * triangles[t + static_cast<size_t>(c)] + a] - x[a];
        len[c] = std::sqrt(r[c][0] * r[c][0] + r[c][1] * r[c][1] + r[c][2] * r[c][2]);
      }
      const double det = r[0][0] * (r[1][1] * r[2][2] - r[1][2] * r[2][1]) -
                         r[0][1] * (r[1][0] * r[2][2] - r[1][2] * r[2][0]) +
                         r[0][2] * (r[1][0] * r[2][1] - r[1][1] * r[2][0]);
      auto dot = [&](int p, int q) {
        return r[p][0] * r[q][0] + r[p][1] * r[q][1] + r[p][2] * r[q][2];
      };
      const double denominator =
          len[0] * len[1] * len[2] + dot(0, 1) * len[2] + dot(1, 2) * len[0] + dot(2, 0) * len[1];
      total += 2.0 * std::atan2(det, denominator);
    }
    return total / (4.0 * M_PI);
  }

 private:
  // Two triangles per boundary quad, turned so their normal points out of the block.
  void add_surface() {
    const int n = cells;
    auto quad = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t d, const double* outward) {
      double e1[3], e2[3];
      for (int k = 0; k < 3; ++k) {
        e1[k] = start[3 * b + k] - start[3 * a + k];
        e2[k] = start[3 * c + k] - start[3 * a + k];
      }
      const double normal[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                                e1[0] * e2[1] - e1[1] * e2[0]};
      const bool flip =
          normal[0] * outward[0] + normal[1] * outward[1] + normal[2] * outward[2] < 0;
      if (flip)
        triangles.insert(triangles.end(), {a, c, b, a, d, c});
      else
        triangles.insert(triangles.end(), {a, b, c, a, c, d});
    };
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        double outward[3] = {0, 0, 0};
        outward[axis] = side ? 1.0 : -1.0;
        for (int u = 0; u < n; ++u)
          for (int w = 0; w < n; ++w) {
            auto at = [&](int du, int dw) {
              int c[3];
              c[axis] = side ? n : 0;
              c[(axis + 1) % 3] = u + du;
              c[(axis + 2) % 3] = w + dw;
              return index(c[0], c[1], c[2]);
            };
            quad(at(0, 0), at(1, 0), at(1, 1), at(0, 1), outward);
          }
      }
  }
};

}  // namespace tacta::testing
