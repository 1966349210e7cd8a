// Repairs and derived data that every model relies on: compact node numbering, positive tets,
// unique edges and the outward boundary surface.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "mesh/geometry.hpp"
#include "mesh/tet_faces.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {

using mesh_detail::point;

[[noreturn]] void fail(const VolumeMesh& mesh, const std::string& message) {
  throw InputError({mesh.source, 0, 0, ""}, message);
}

void check_input(const VolumeMesh& mesh) {
  if (mesh.positions.size() % 3 != 0) fail(mesh, "positions must hold 3 numbers per node");
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    if (!std::isfinite(mesh.positions[i]))
      fail(mesh, "node " + std::to_string(i / 3) + " has a NaN or infinite coordinate");
  }
  if (mesh.tets.size() % 4 != 0 || mesh.quads.size() % 4 != 0 || mesh.triangles.size() % 3 != 0) {
    fail(mesh, "element index arrays must hold 4 per tet or quad and 3 per triangle");
  }
  if (mesh.dimension == 3 && mesh.tets.empty()) fail(mesh, "the mesh has no tetrahedra");
  if (mesh.dimension == 2 && mesh.quads.empty() && mesh.triangles.empty())
    fail(mesh, "the planar mesh has no elements");
  if (mesh.dimension != 2 && mesh.dimension != 3) fail(mesh, "dimension must be 2 or 3");
  const size_t n = mesh.node_count();
  auto check = [&](const std::vector<uint32_t>& indices, const char* what, size_t per) {
    for (size_t i = 0; i < indices.size(); ++i) {
      if (indices[i] >= n) {
        fail(mesh, std::string(what) + " " + std::to_string(i / per) + " refers to node " +
                       std::to_string(indices[i]) + ", outside [0, " + std::to_string(n) + ")");
      }
    }
  };
  check(mesh.tets, "tet", 4);
  check(mesh.quads, "quad", 4);
  check(mesh.triangles, "triangle", 3);
}

// Drops nodes that no element uses and renumbers the rest in their old order.
void remove_unreferenced(VolumeMesh& mesh, LoadReport& report) {
  const size_t n = mesh.node_count();
  std::vector<uint32_t> remap(n, UINT32_MAX);
  auto mark = [&](const std::vector<uint32_t>& indices) {
    for (uint32_t i : indices) remap[i] = 0;
  };
  mark(mesh.tets);
  mark(mesh.quads);
  if (mesh.dimension == 2) mark(mesh.triangles);
  uint32_t next = 0;
  for (size_t i = 0; i < n; ++i) {
    if (remap[i] == 0) {
      for (int k = 0; k < 3; ++k)
        mesh.positions[3 * next + static_cast<size_t>(k)] =
            mesh.positions[3 * i + static_cast<size_t>(k)];
      remap[i] = next++;
    }
  }
  if (next == n) return;
  report.removed_nodes += n - next;
  report.warnings.push_back(std::to_string(n - next) + " nodes that no element uses were removed");
  mesh.positions.resize(3 * size_t{next});
  for (auto* indices : {&mesh.tets, &mesh.quads, &mesh.triangles}) {
    for (uint32_t& i : *indices) i = remap[i];
  }
}

void orient_tets(VolumeMesh& mesh, LoadReport& report) {
  std::vector<char> swapped(mesh.tet_count(), 0);
  size_t inverted = 0;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    uint32_t* v = &mesh.tets[4 * t];
    Vec3 a = point(mesh.positions, v[0]), b = point(mesh.positions, v[1]),
         c = point(mesh.positions, v[2]), d = point(mesh.positions, v[3]);
    double six_volume = triple(sub(b, a), sub(c, a), sub(d, a));
    double longest = std::max({distance(b, a), distance(c, a), distance(d, a), distance(c, b),
                               distance(d, b), distance(d, c)});
    if (!(std::abs(six_volume) > mesh_detail::kFlatVolume * longest * longest * longest)) {
      fail(mesh, "tet " + std::to_string(t) + " (nodes " + std::to_string(v[0]) + " " +
                     std::to_string(v[1]) + " " + std::to_string(v[2]) + " " +
                     std::to_string(v[3]) + ", counted from 0) has zero volume");
    }
    if (six_volume < 0) {
      std::swap(v[2], v[3]);
      swapped[t] = 1;
      ++inverted;
    }
  }
  if (inverted == 0) return;
  report.inverted_tets += inverted;
  report.warnings.push_back(std::to_string(inverted) + " inverted tets were re-oriented");
  if (mesh.embedding) {
    Embedding& e = *mesh.embedding;
    for (size_t v = 0; v < e.element.size(); ++v) {
      if (e.element[v] < swapped.size() && swapped[e.element[v]])
        std::swap(e.weights[4 * v + 2], e.weights[4 * v + 3]);
    }
  }
}

// Planar elements counter-clockwise seen from +z; a flat one is an error.
void orient_planar(VolumeMesh& mesh, std::vector<uint32_t>& elements, size_t per,
                   const char* what) {
  for (size_t e = 0; e < elements.size() / per; ++e) {
    uint32_t* v = &elements[per * e];
    double twice_area = 0, longest = 0;
    for (size_t k = 0; k < per; ++k) {
      Vec3 p = point(mesh.positions, v[k]), q = point(mesh.positions, v[(k + 1) % per]);
      twice_area += p[0] * q[1] - q[0] * p[1];
      longest = std::max(longest, distance(q, p));
    }
    if (!(std::abs(twice_area) > mesh_detail::kFlatVolume * longest * longest))
      fail(mesh, std::string(what) + " " + std::to_string(e) + " has zero area");
    if (twice_area < 0) std::reverse(v, v + per);
  }
}

}  // namespace

void finalize(VolumeMesh& mesh, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  check_input(mesh);
  remove_unreferenced(mesh, r);
  if (mesh.dimension == 3) {
    orient_tets(mesh, r);
    mesh_detail::build_boundary(mesh);
  } else {
    orient_planar(mesh, mesh.quads, 4, "quad");
    orient_planar(mesh, mesh.triangles, 3, "triangle");
  }
  mesh_detail::build_edges(mesh);
}

}  // namespace tacta
