#include "tacta/models/test_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "tacta/models/lame.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models {

tacta_model_setup TestMesh::setup(const tacta_mesh_view& view, const tacta_material& material,
                                  const tacta_param_value* params, uint32_t param_count,
                                  double dt) const {
  return {sizeof(tacta_model_setup),
          &view,
          &material,
          masses.data(),
          fixed.data(),
          params,
          param_count,
          dt,
          nullptr};
}

tacta_mesh_view TestMesh::view() const {
  tacta_mesh_view v{};
  v.node_count = node_count();
  v.rest_positions = positions.data();
  v.tet_count = static_cast<uint32_t>(tets.size() / 4);
  v.tets = tets.data();
  v.triangle_count = static_cast<uint32_t>(triangles.size() / 3);
  v.triangles = triangles.data();
  v.quad_count = static_cast<uint32_t>(quads.size() / 4);
  v.quads = quads.data();
  v.edge_count = static_cast<uint32_t>(edges.size() / 2);
  v.edges = edges.data();
  v.dimension = dimension;
  return v;
}

double TestMesh::mean_displacement_on_plane(const double* current, int axis, double value,
                                            int component, double tolerance) const {
  double sum = 0.0;
  int count = 0;
  for (uint32_t i = 0; i < node_count(); ++i)
    if (std::abs(positions[3 * i + axis] - value) <= tolerance) {
      sum += current[3 * i + component] - positions[3 * i + component];
      ++count;
    }
  return count > 0 ? sum / count : 0.0;
}

void TestMesh::fix_plane(int axis, double value, double tolerance) {
  for (uint32_t i = 0; i < node_count(); ++i)
    if (std::abs(positions[3 * i + static_cast<uint32_t>(axis)] - value) <= tolerance) fixed[i] = 1;
}

tacta_material make_material(double youngs_modulus, double poisson_ratio, double density) {
  const Lame l = lame_from_young(youngs_modulus, poisson_ratio);
  return {youngs_modulus, poisson_ratio, density, l.lambda, l.mu, 0.0, 0.0};
}

tacta_material make_material_lame(double lambda, double mu, double density) {
  return {
      young_from_lame(lambda, mu), poisson_from_lame(lambda, mu), density, lambda, mu, 0.0, 0.0};
}

namespace {

std::vector<double> grid_nodes(std::array<uint32_t, 3> n, std::array<double, 3> size) {
  std::vector<double> p;
  for (uint32_t k = 0; k <= n[2]; ++k)
    for (uint32_t j = 0; j <= n[1]; ++j)
      for (uint32_t i = 0; i <= n[0]; ++i) {
        p.push_back(n[0] ? size[0] * i / n[0] : 0.0);
        p.push_back(n[1] ? size[1] * j / n[1] : 0.0);
        p.push_back(n[2] ? size[2] * k / n[2] : 0.0);
      }
  return p;
}

// Dual-cell length of grid index i along an axis with n cells of length h: h/2 at the ends.
double dual_length(uint32_t i, uint32_t n, double h) {
  if (n == 0) return 1.0;  // a flat axis: unit thickness
  return (i == 0 || i == n) ? h / 2 : h;
}

}  // namespace

std::vector<uint32_t> edges_of_tets(const std::vector<uint32_t>& tets) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (size_t t = 0; t + 3 < tets.size(); t += 4)
    for (size_t a = 0; a < 4; ++a)
      for (size_t b = a + 1; b < 4; ++b)
        pairs.emplace_back(std::min(tets[t + a], tets[t + b]), std::max(tets[t + a], tets[t + b]));
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<uint32_t> edges;
  for (auto [a, b] : pairs) edges.insert(edges.end(), {a, b});
  return edges;
}

std::vector<uint32_t> boundary_of_tets(const std::vector<uint32_t>& tets) {
  // Faces opposite each vertex, oriented outward for a positively oriented tet.
  static constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  std::map<std::array<uint32_t, 3>, std::pair<int, std::array<uint32_t, 3>>> faces;
  for (size_t t = 0; t + 3 < tets.size(); t += 4)
    for (const auto& f : kFace) {
      std::array<uint32_t, 3> tri{tets[t + f[0]], tets[t + f[1]], tets[t + f[2]]};
      std::array<uint32_t, 3> key = tri;
      std::sort(key.begin(), key.end());
      auto& entry = faces[key];
      ++entry.first;
      entry.second = tri;
    }
  std::vector<uint32_t> out;
  for (const auto& [key, entry] : faces)
    if (entry.first == 1) out.insert(out.end(), entry.second.begin(), entry.second.end());
  return out;
}

TestMesh box_tet_mesh(std::array<uint32_t, 3> n, std::array<double, 3> size, double density,
                      GridSplit split) {
  TestMesh m;
  m.positions = grid_nodes(n, size);
  auto id = [&](uint32_t i, uint32_t j, uint32_t k) {
    return i + (n[0] + 1) * (j + (n[1] + 1) * k);
  };
  // Six paths across the cell's diagonal, one axis step at a time: one tet each. The symmetric
  // split (as the engine's grids and SOFA's Hexa2Tetra with swapping): along each axis, odd cells
  // start from the far side, so each cell mirrors its neighbours and no diagonal is preferred.
  static constexpr int kAxisOrder[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                           {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (uint32_t k = 0; k < n[2]; ++k)
    for (uint32_t j = 0; j < n[1]; ++j)
      for (uint32_t i = 0; i < n[0]; ++i)
        for (const auto& order : kAxisOrder) {
          const uint32_t odd =
              split == GridSplit::kSymmetric ? 1u : 0u;  // mirror odd cells or none
          const std::array<uint32_t, 3> cell{i & odd, j & odd, k & odd};
          std::array<uint32_t, 3> c{i + cell[0], j + cell[1], k + cell[2]};
          std::array<uint32_t, 4> tet{};
          tet[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            const auto axis = static_cast<size_t>(order[s]);
            c[axis] = cell[axis] ? c[axis] - 1 : c[axis] + 1;
            tet[static_cast<size_t>(s) + 1] = id(c[0], c[1], c[2]);
          }
          const double* p = m.positions.data();
          if (tet_signed_volume(node_position(p, tet[0]), node_position(p, tet[1]),
                                node_position(p, tet[2]), node_position(p, tet[3])) < 0)
            std::swap(tet[2], tet[3]);
          m.tets.insert(m.tets.end(), tet.begin(), tet.end());
        }
  m.edges = edges_of_tets(m.tets);
  m.triangles = boundary_of_tets(m.tets);
  m.masses = lumped_tet_masses(m.positions, m.tets, density);
  m.fixed.assign(m.node_count(), 0);
  return m;
}

TestMesh grid_edge_mesh(std::array<uint32_t, 3> n, std::array<double, 3> size, double density) {
  TestMesh m;
  m.positions = grid_nodes(n, size);
  auto id = [&](uint32_t i, uint32_t j, uint32_t k) {
    return i + (n[0] + 1) * (j + (n[1] + 1) * k);
  };
  const double h[3] = {n[0] ? size[0] / n[0] : 1.0, n[1] ? size[1] / n[1] : 1.0,
                       n[2] ? size[2] / n[2] : 1.0};
  for (uint32_t k = 0; k <= n[2]; ++k)
    for (uint32_t j = 0; j <= n[1]; ++j)
      for (uint32_t i = 0; i <= n[0]; ++i) {
        const uint32_t a = id(i, j, k);
        if (i < n[0]) m.edges.insert(m.edges.end(), {a, id(i + 1, j, k)});
        if (j < n[1]) m.edges.insert(m.edges.end(), {a, id(i, j + 1, k)});
        if (k < n[2]) m.edges.insert(m.edges.end(), {a, id(i, j, k + 1)});
        m.masses.push_back(density * dual_length(i, n[0], h[0]) * dual_length(j, n[1], h[1]) *
                           dual_length(k, n[2], h[2]));
      }
  m.fixed.assign(m.node_count(), 0);
  m.dimension = n[2] == 0 ? 2u : 3u;
  return m;
}

TestMesh quad_grid_mesh(uint32_t nx, uint32_t ny, double sx, double sy, double density) {
  TestMesh m = grid_edge_mesh({nx, ny, 0}, {sx, sy, 0.0}, density);
  for (uint32_t j = 0; j < ny; ++j)
    for (uint32_t i = 0; i < nx; ++i) {
      const uint32_t a = i + (nx + 1) * j;
      m.quads.insert(m.quads.end(), {a, a + 1, a + nx + 2, a + nx + 1});
    }
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (size_t e = 0; e < m.edges.size(); e += 2) pairs.emplace_back(m.edges[e], m.edges[e + 1]);
  std::sort(pairs.begin(), pairs.end());
  m.edges.clear();
  for (auto [a, b] : pairs) m.edges.insert(m.edges.end(), {a, b});
  m.dimension = 2;
  return m;
}

}  // namespace tacta::models
