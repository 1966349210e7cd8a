// The scene's built-in bodies: box and beam grids of tets, the planar quad grid, and a ball.
#include <algorithm>
#include <cmath>
#include <string>

#include "mesh/grid_tets.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/vec3.hpp"

namespace tacta {

namespace {

void check_grid(const char* name, const Vec3& size, const std::array<int, 3>& cells, int axes) {
  int64_t nodes = 1;
  for (int a = 0; a < axes; ++a) {
    if (!(size[static_cast<size_t>(a)] > 0) || !std::isfinite(size[static_cast<size_t>(a)])) {
      throw InputError({name, 0, 0, ""}, "size must be positive and finite on every axis");
    }
    if (cells[static_cast<size_t>(a)] < 1)
      throw InputError({name, 0, 0, ""}, "cells must be at least 1 on every axis");
    nodes *= cells[static_cast<size_t>(a)] + 1;
    if (nodes > kMaxGridNodes)
      throw InputError({name, 0, 0, ""},
                       "more than " + std::to_string(kMaxGridNodes) + " grid nodes");
  }
}

// mirror_about_centre: each octant of the grid splits its cells with the diagonal pointing away
// from the grid centre (the ball needs it: a tet never has all four nodes on one spherical shell).
VolumeMesh hex_grid(const char* name, const Vec3& size, const std::array<int, 3>& cells,
                    const Vec3& origin, bool mirror_about_centre = false) {
  check_grid(name, size, cells, 3);
  const uint32_t nx = static_cast<uint32_t>(cells[0]), ny = static_cast<uint32_t>(cells[1]),
                 nz = static_cast<uint32_t>(cells[2]);
  VolumeMesh mesh;
  mesh.source = name;
  auto node = [&](uint32_t i, uint32_t j, uint32_t k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  mesh.positions.reserve(3 * size_t{nx + 1} * (ny + 1) * (nz + 1));
  for (uint32_t k = 0; k <= nz; ++k) {
    for (uint32_t j = 0; j <= ny; ++j) {
      for (uint32_t i = 0; i <= nx; ++i) {
        mesh.positions.push_back(origin[0] + size[0] * i / nx);
        mesh.positions.push_back(origin[1] + size[1] * j / ny);
        mesh.positions.push_back(origin[2] + size[2] * k / nz);
      }
    }
  }
  mesh.tets.reserve(24 * size_t{nx} * ny * nz);
  for (uint32_t k = 0; k < nz; ++k) {
    for (uint32_t j = 0; j < ny; ++j) {
      for (uint32_t i = 0; i < nx; ++i) {
        uint32_t corner[8];
        for (uint32_t c = 0; c < 8; ++c)
          corner[c] = node(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
        unsigned mirror = mesh_detail::alternating_mirror(i, j, k);
        if (mirror_about_centre) {
          mirror = (2 * i < nx ? 1u : 0u) | (2 * j < ny ? 2u : 0u) | (2 * k < nz ? 4u : 0u);
        }
        mesh_detail::append_cell_tets(corner, mesh.tets, mirror);
      }
    }
  }
  finalize(mesh);
  return mesh;
}

}  // namespace

VolumeMesh make_box_grid(const Vec3& size, const std::array<int, 3>& cells, const Vec3& origin) {
  return hex_grid("box_grid", size, cells, origin);
}

VolumeMesh make_beam_grid(const Vec3& size, const std::array<int, 3>& cells, const Vec3& origin) {
  return hex_grid("beam_grid", size, cells, origin);
}

VolumeMesh make_quad_grid(const Vec3& size, const std::array<int, 3>& cells, const Vec3& origin) {
  check_grid("quad_grid", size, cells, 2);
  const uint32_t nx = static_cast<uint32_t>(cells[0]), ny = static_cast<uint32_t>(cells[1]);
  VolumeMesh mesh;
  mesh.source = "quad_grid";
  mesh.dimension = 2;
  for (uint32_t j = 0; j <= ny; ++j) {
    for (uint32_t i = 0; i <= nx; ++i) {
      mesh.positions.push_back(origin[0] + size[0] * i / nx);
      mesh.positions.push_back(origin[1] + size[1] * j / ny);
      mesh.positions.push_back(origin[2]);
    }
  }
  for (uint32_t j = 0; j < ny; ++j) {
    for (uint32_t i = 0; i < nx; ++i) {
      uint32_t sw = i + (nx + 1) * j, se = sw + 1, nw = sw + nx + 1, ne = nw + 1;
      mesh.quads.insert(mesh.quads.end(), {sw, se, ne, nw});
      mesh.triangles.insert(mesh.triangles.end(), {sw, se, ne, sw, ne, nw});
    }
  }
  finalize(mesh);
  return mesh;
}

VolumeMesh make_sphere(double radius, const Vec3& centre, int subdivisions) {
  if (!(radius > 0) || !std::isfinite(radius))
    throw InputError({"sphere", 0, 0, ""}, "radius must be positive and finite");
  if (subdivisions < 0 || subdivisions > 4)
    throw InputError({"sphere", 0, 0, ""}, "subdivisions must be in [0, 4]");
  const int n = 2 << subdivisions;  // cells a side: 2, 4, 8, 16, 32
  VolumeMesh mesh = hex_grid("sphere", {2, 2, 2}, {n, n, n}, {-1, -1, -1}, true);
  // Each cube shell max(|x|,|y|,|z|) = s goes onto the sphere |p| = s: p -> p s / |p|.
  for (size_t i = 0; i < mesh.node_count(); ++i) {
    double* p = &mesh.positions[3 * i];
    double shell = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
    double length = norm(p);
    double factor = length > 0 ? radius * shell / length : 0;
    for (int k = 0; k < 3; ++k) p[k] = centre[static_cast<size_t>(k)] + factor * p[k];
  }
  mesh.source = "sphere";
  finalize(mesh);
  return mesh;
}

}  // namespace tacta
