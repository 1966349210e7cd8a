#include "mesh/tet_faces.hpp"

#include <algorithm>
#include <tuple>

namespace tacta::mesh_detail {

namespace {

// `items` ordered by first(item) < buckets, keeping their order within a bucket (a counting
// sort); start[b] .. start[b + 1] is bucket b in the result.
template <class Item, class First>
std::vector<Item> bucketed(const std::vector<Item>& items, uint32_t buckets, First&& first,
                           std::vector<uint32_t>& start) {
  start.assign(size_t{buckets} + 1, 0);
  for (const Item& item : items) ++start[first(item) + 1];
  for (size_t b = 1; b <= buckets; ++b) start[b] += start[b - 1];
  std::vector<uint32_t> fill(start.begin(), start.end() - 1);
  std::vector<Item> out(items.size());
  for (const Item& item : items) out[fill[first(item)]++] = item;
  return out;
}

}  // namespace

// Bucketed by the smallest node (each bucket stays in `order`), then each bucket sorted on the
// other two nodes: the order of one sort by (key, order) in about linear time, since a node is
// the smallest of a few tens of faces.
std::vector<TetFace> sorted_tet_faces(const std::vector<uint32_t>& tets) {
  std::vector<TetFace> faces;
  faces.reserve(tets.size());
  uint32_t nodes = 0;
  for (uint32_t t = 0; t < tets.size() / 4; ++t) {
    for (uint32_t f = 0; f < 4; ++f) {
      std::array<uint32_t, 3> key;
      for (size_t k = 0; k < 3; ++k) key[k] = tets[4 * size_t{t} + kTetFaces[f][k]];
      std::sort(key.begin(), key.end());
      nodes = std::max(nodes, key[2] + 1);
      faces.push_back({key, 4 * t + f});
    }
  }
  std::vector<uint32_t> start;
  faces = bucketed(
      faces, nodes, [](const TetFace& face) { return face.key[0]; }, start);
  for (size_t b = 0; b < nodes; ++b)
    std::sort(faces.begin() + start[b], faces.begin() + start[b + 1],
              [](const TetFace& x, const TetFace& y) {
                return std::tie(x.key[1], x.key[2], x.order) <
                       std::tie(y.key[1], y.key[2], y.order);
              });
  return faces;
}

void build_boundary(VolumeMesh& mesh) {
  const std::vector<TetFace> faces = sorted_tet_faces(mesh.tets);
  std::vector<uint32_t> single;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && same_face(faces[j], faces[i])) ++j;
    if (j - i == 1) single.push_back(faces[i].order);
    i = j;
  }
  set_boundary(mesh, std::move(single));
}

void set_boundary(VolumeMesh& mesh, std::vector<uint32_t> orders) {
  std::sort(orders.begin(), orders.end());
  mesh.triangles.clear();
  mesh.triangles.reserve(3 * orders.size());
  for (uint32_t order : orders) {
    const uint32_t t = order / 4, f = order % 4;
    for (size_t k = 0; k < 3; ++k)
      mesh.triangles.push_back(mesh.tets[4 * size_t{t} + kTetFaces[f][k]]);
  }
}

void build_edges(VolumeMesh& mesh) {
  using Edge = std::array<uint32_t, 2>;
  std::vector<Edge> edges;
  uint32_t nodes = 0;
  auto add = [&](uint32_t a, uint32_t b) {
    edges.push_back({std::min(a, b), std::max(a, b)});
    nodes = std::max(nodes, edges.back()[1] + 1);
  };
  if (mesh.dimension == 3) {
    edges.reserve(6 * mesh.tet_count());
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
  // Ascending and unique: bucketed by the first node, then each node's few second nodes sorted.
  std::vector<uint32_t> start;
  edges = bucketed(
      edges, nodes, [](const Edge& e) { return e[0]; }, start);
  auto kept = edges.begin();
  for (size_t b = 0; b < nodes; ++b) {
    const auto first = edges.begin() + start[b], last = edges.begin() + start[b + 1];
    std::sort(first, last, [](const Edge& x, const Edge& y) { return x[1] < y[1]; });
    for (auto e = first; e != last; ++e)
      if (e == first || (*e)[1] != (*(e - 1))[1]) *kept++ = *e;
  }
  edges.erase(kept, edges.end());
  mesh.edges.clear();
  mesh.edges.reserve(2 * edges.size());
  for (const Edge& e : edges) mesh.edges.insert(mesh.edges.end(), e.begin(), e.end());
}

}  // namespace tacta::mesh_detail
