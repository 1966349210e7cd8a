#include "mesh/tet_faces.hpp"

#include <algorithm>

namespace tacta::mesh_detail {

std::vector<TetFace> sorted_tet_faces(const std::vector<uint32_t>& tets) {
  std::vector<TetFace> faces;
  faces.reserve(tets.size());
  for (uint32_t t = 0; t < tets.size() / 4; ++t) {
    for (uint32_t f = 0; f < 4; ++f) {
      std::array<uint32_t, 3> key;
      for (size_t k = 0; k < 3; ++k) key[k] = tets[4 * size_t{t} + kTetFaces[f][k]];
      std::sort(key.begin(), key.end());
      faces.push_back({key, 4 * t + f});
    }
  }
  std::sort(faces.begin(), faces.end(), [](const TetFace& x, const TetFace& y) {
    return x.key != y.key ? x.key < y.key : x.order < y.order;
  });
  return faces;
}

void build_boundary(VolumeMesh& mesh) {
  const std::vector<TetFace> faces = sorted_tet_faces(mesh.tets);
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
    const uint32_t t = order / 4, f = order % 4;
    for (size_t k = 0; k < 3; ++k)
      mesh.triangles.push_back(mesh.tets[4 * size_t{t} + kTetFaces[f][k]]);
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

}  // namespace tacta::mesh_detail
