// Repairs and derived data that every model relies on: compact node numbering, positive tets,
// unique edges and the outward boundary surface.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "mesh/geometry.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {

using mesh_detail::point;

constexpr double kZeroVolume = 1e-12;  // |6V| below this times (longest edge)^3 is a flat tet

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
    if (!(std::abs(six_volume) > kZeroVolume * longest * longest * longest)) {
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
    if (!(std::abs(twice_area) > kZeroVolume * longest * longest))
      fail(mesh, std::string(what) + " " + std::to_string(e) + " has zero area");
    if (twice_area < 0) std::reverse(v, v + per);
  }
}

void build_edges(VolumeMesh& mesh) {
  std::vector<std::array<uint32_t, 2>> edges;
  auto add = [&](uint32_t a, uint32_t b) { edges.push_back({std::min(a, b), std::max(a, b)}); };
  if (mesh.dimension == 3) {
    for (size_t t = 0; t < mesh.tet_count(); ++t) {
      const uint32_t* v = &mesh.tets[4 * t];
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) add(v[i], v[j]);
    }
  } else if (!mesh.quads.empty()) {
    for (size_t q = 0; q < mesh.quads.size() / 4; ++q)
      for (size_t k = 0; k < 4; ++k) add(mesh.quads[4 * q + k], mesh.quads[4 * q + (k + 1) % 4]);
  } else {
    for (size_t t = 0; t < mesh.triangles.size() / 3; ++t)
      for (size_t k = 0; k < 3; ++k)
        add(mesh.triangles[3 * t + k], mesh.triangles[3 * t + (k + 1) % 3]);
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  mesh.edges.clear();
  mesh.edges.reserve(2 * edges.size());
  for (const auto& e : edges) mesh.edges.insert(mesh.edges.end(), e.begin(), e.end());
}

// Faces used by one tet only, each kept with the winding that points out of its tet.
void build_boundary(VolumeMesh& mesh) {
  // Outward faces of a positive tet (a, b, c, d).
  static constexpr int kFaces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  struct Face {
    std::array<uint32_t, 3> key;
    uint32_t order;  // tet * 4 + local face: keeps the output in tet order
  };
  std::vector<Face> faces;
  faces.reserve(4 * mesh.tet_count());
  for (uint32_t t = 0; t < mesh.tet_count(); ++t) {
    for (uint32_t f = 0; f < 4; ++f) {
      std::array<uint32_t, 3> key;
      for (int k = 0; k < 3; ++k)
        key[static_cast<size_t>(k)] = mesh.tets[4 * t + static_cast<uint32_t>(kFaces[f][k])];
      std::sort(key.begin(), key.end());
      faces.push_back({key, 4 * t + f});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const Face& x, const Face& y) { return x.key < y.key; });
  std::vector<uint32_t> single;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i == 1) single.push_back(faces[i].order);
    i = j;
  }
  std::sort(single.begin(), single.end());
  mesh.triangles.clear();
  mesh.triangles.reserve(3 * single.size());
  for (uint32_t order : single) {
    uint32_t t = order / 4, f = order % 4;
    for (int k = 0; k < 3; ++k)
      mesh.triangles.push_back(mesh.tets[4 * t + static_cast<uint32_t>(kFaces[f][k])]);
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
    build_boundary(mesh);
  } else {
    orient_planar(mesh, mesh.quads, 4, "quad");
    orient_planar(mesh, mesh.triangles, 3, "triangle");
  }
  build_edges(mesh);
}

}  // namespace tacta
