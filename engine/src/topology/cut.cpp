// cut_mesh: which tets a blade removes, or which faces it opens and which nodes that splits, and
// the new rest mesh built from the result.
#include <algorithm>
#include <numeric>
#include <optional>

#include "mesh/tet_faces.hpp"
#include "tacta/vec3.hpp"
#include "topology/blade.hpp"
#include "topology/cut_mesh.hpp"

namespace tacta {

namespace {

using mesh_detail::kTetFaces;
using mesh_detail::TetFace;
using topology_detail::BladeTriangle;
using topology_detail::Box;

constexpr double kRoundOff = 1e-12;  // relative to the body's size: box padding

std::array<Vec3, 4> tet_points(std::span<const double> positions, const uint32_t* nodes) {
  return {point_at(positions.data(), nodes[0]), point_at(positions.data(), nodes[1]),
          point_at(positions.data(), nodes[2]), point_at(positions.data(), nodes[3])};
}

// The edit that changes nothing: rest as it is, every node and tet its own source.
TopologyEdit unchanged(const VolumeMesh& rest, std::span<const uint8_t> rest_cut) {
  TopologyEdit edit;
  edit.mesh = rest;
  edit.mesh.embedding.reset();
  edit.node_source.resize(rest.node_count());
  std::iota(edit.node_source.begin(), edit.node_source.end(), 0u);
  edit.tet_source.resize(rest.tet_count());
  std::iota(edit.tet_source.begin(), edit.tet_source.end(), 0u);
  if (rest_cut.size() == rest.triangles.size() / 3)
    edit.cut_triangle.assign(rest_cut.begin(), rest_cut.end());
  else
    edit.cut_triangle.assign(rest.triangles.size() / 3, 0);
  edit.exposed.assign(rest.triangles.size() / 3, 0);
  return edit;
}

std::string check_input(const VolumeMesh& rest, std::span<const uint8_t> rest_cut,
                        std::span<const double> positions, std::span<const double> triangles) {
  if (rest.dimension != 3 || rest.tets.empty() || rest.tets.size() % 4 != 0)
    return "only a tetrahedral body can be cut";
  if (positions.size() != rest.positions.size())
    return "the cut was given " + std::to_string(positions.size()) +
           " position numbers for a body of " + std::to_string(rest.node_count()) +
           " nodes (3 per node expected)";
  for (size_t i = 0; i < positions.size(); i += 3)
    if (!is_finite(point_at(&positions[i], 0)))
      return "node " + std::to_string(i / 3) + " of the body is not at a finite position";
  if (triangles.size() % 9 != 0)
    return "expected 9 numbers per blade triangle (three corners x, y, z in m), found " +
           std::to_string(triangles.size()) + " numbers";
  if (!rest_cut.empty() && rest_cut.size() != rest.triangles.size() / 3)
    return "the cut marks have " + std::to_string(rest_cut.size()) + " entries for " +
           std::to_string(rest.triangles.size() / 3) + " boundary triangles";
  for (uint32_t n : rest.tets)
    if (n >= rest.node_count()) return "a tet refers to a node past the mesh's nodes";
  return {};
}

// The blade's triangles near the body, the box around them all, and the padding (m) box tests
// use. A box that misses `reach` misses every triangle's box: one test instead of one a triangle.
struct Blade {
  std::vector<BladeTriangle> triangles;
  Box reach = Box::empty();
  double pad = 0;
};
Blade near_blade(std::span<const double> positions, std::span<const double> triangles) {
  Box body = Box::empty();
  for (size_t i = 0; i + 3 <= positions.size(); i += 3) body.include(point_at(&positions[i], 0));
  double extent = 0;
  for (size_t a = 0; a < 3; ++a) extent = std::max(extent, body.hi[a] - body.lo[a]);
  Blade blade;
  blade.pad = kRoundOff * extent;
  for (const BladeTriangle& t : topology_detail::cutting_triangles(triangles))
    if (t.box.meets(body, blade.pad)) {
      blade.triangles.push_back(t);
      blade.reach.include(t.box.lo), blade.reach.include(t.box.hi);
    }
  return blade;
}

// Removal: 1 per tet the blade passes through.
std::vector<uint8_t> tets_cut(const VolumeMesh& rest, std::span<const double> positions,
                              const Blade& blade) {
  std::vector<uint8_t> cut(rest.tet_count(), 0);
  for (size_t t = 0; t < rest.tet_count(); ++t) {
    const std::array<Vec3, 4> x = tet_points(positions, &rest.tets[4 * t]);
    Box box = Box::empty();
    for (const Vec3& p : x) box.include(p);
    if (!blade.reach.meets(box, blade.pad)) continue;
    for (const BladeTriangle& triangle : blade.triangles) {
      if (triangle.box.meets(box, blade.pad) &&
          topology_detail::triangle_meets_tet_interior(triangle, x)) {
        cut[t] = 1;
        break;
      }
    }
  }
  return cut;
}

struct Removal {
  std::vector<uint32_t> tets, node_source, tet_source;
};
// The crack's faces whose nodes all remain, in the new numbering (node_source: new -> old).
std::vector<FaceNodes> renumbered(std::span<const FaceNodes> crack,
                                  const std::vector<uint32_t>& node_source, size_t old_nodes) {
  std::vector<uint32_t> new_index(old_nodes, UINT32_MAX);
  for (uint32_t n = 0; n < node_source.size(); ++n) new_index[node_source[n]] = n;
  std::vector<FaceNodes> out;
  for (const FaceNodes& face : crack) {
    FaceNodes now;
    bool kept = true;
    for (size_t k = 0; k < 3; ++k) {
      kept = kept && face[k] < old_nodes && new_index[face[k]] != UINT32_MAX;
      now[k] = kept ? new_index[face[k]] : 0;
    }
    if (!kept) continue;
    std::sort(now.begin(), now.end());
    out.push_back(now);
  }
  std::sort(out.begin(), out.end());
  return out;
}

Removal remove_tets(const VolumeMesh& rest, const std::vector<uint8_t>& cut) {
  Removal r;
  std::vector<uint32_t> new_index(rest.node_count(), UINT32_MAX);
  for (uint32_t t = 0; t < rest.tet_count(); ++t)
    if (!cut[t])
      for (size_t k = 0; k < 4; ++k) new_index[rest.tets[4 * size_t{t} + k]] = 0;
  for (uint32_t n = 0; n < rest.node_count(); ++n) {
    if (new_index[n] == UINT32_MAX) continue;
    new_index[n] = static_cast<uint32_t>(r.node_source.size());
    r.node_source.push_back(n);
  }
  for (uint32_t t = 0; t < rest.tet_count(); ++t) {
    if (cut[t]) continue;
    r.tet_source.push_back(t);
    for (size_t k = 0; k < 4; ++k) r.tets.push_back(new_index[rest.tets[4 * size_t{t} + k]]);
  }
  return r;
}

// An interior face: the two faces (tet * 4 + local face) that are one.
struct SharedFace {
  uint32_t first, second;
  bool crossed = false;
};

// Compressed lists: item i's entries are entries[start[i] .. start[i + 1]).
struct Lists {
  std::vector<uint32_t> start, entries;
  std::span<const uint32_t> of(size_t i) const {
    return {entries.data() + start[i], entries.data() + start[i + 1]};
  }
};
template <class ForEach>
Lists make_lists(size_t items, ForEach&& for_each) {
  Lists lists;
  lists.start.assign(items + 1, 0);
  for_each([&](uint32_t item, uint32_t) { ++lists.start[item + 1]; });
  for (size_t i = 1; i <= items; ++i) lists.start[i] += lists.start[i - 1];
  lists.entries.resize(lists.start.back());
  std::vector<uint32_t> fill(lists.start.begin(), lists.start.end() - 1);
  for_each([&](uint32_t item, uint32_t entry) { lists.entries[fill[item]++] = entry; });
  return lists;
}

struct Separation {
  std::vector<uint32_t> tets, node_source;
  size_t faces_separated = 0;
  std::vector<uint32_t> opened;  // both sides (tet * 4 + local face) of each face that opened
  std::vector<FaceNodes> crack;  // crossed faces still closed, new numbering, sorted
};

// Separation: the new tets once every node on a crossed face is given one copy per group of
// its tets that still hold together through uncrossed faces around it.
Separation separate(const VolumeMesh& rest, const std::vector<SharedFace>& faces) {
  const size_t nodes = rest.node_count();
  Separation s;
  s.tets = rest.tets;
  s.node_source.resize(nodes);
  std::iota(s.node_source.begin(), s.node_source.end(), 0u);
  auto face_node = [&](uint32_t order, size_t k) {
    return rest.tets[4 * size_t{order / 4} + kTetFaces[order % 4][k]];
  };
  const Lists tets_of = make_lists(nodes, [&](auto&& add) {
    for (uint32_t t = 0; t < rest.tet_count(); ++t)
      for (size_t k = 0; k < 4; ++k) add(rest.tets[4 * size_t{t} + k], t);
  });
  const Lists faces_of = make_lists(nodes, [&](auto&& add) {
    for (uint32_t f = 0; f < faces.size(); ++f)
      for (size_t k = 0; k < 3; ++k) add(face_node(faces[f].first, k), f);
  });
  std::vector<uint32_t> group, parent;
  for (uint32_t n = 0; n < nodes; ++n) {
    const std::span<const uint32_t> around = faces_of.of(n);
    if (std::none_of(around.begin(), around.end(), [&](uint32_t f) { return faces[f].crossed; }))
      continue;
    // Union-find over the tets around n (listed in ascending order), joined by uncrossed faces.
    const std::span<const uint32_t> tets = tets_of.of(n);
    parent.resize(tets.size());
    std::iota(parent.begin(), parent.end(), 0u);
    auto local = [&](uint32_t tet) {
      return static_cast<uint32_t>(std::lower_bound(tets.begin(), tets.end(), tet) - tets.begin());
    };
    auto root = [&](uint32_t i) {
      while (parent[i] != i) i = parent[i] = parent[parent[i]];
      return i;
    };
    for (uint32_t f : around) {
      if (faces[f].crossed) continue;
      const uint32_t a = root(local(faces[f].first / 4)), b = root(local(faces[f].second / 4));
      parent[std::max(a, b)] = std::min(a, b);  // the root is the group's first tet
    }
    // The group of the first tet keeps n; every other group gets a copy, in tet order.
    group.assign(tets.size(), UINT32_MAX);
    for (uint32_t i = 0; i < tets.size(); ++i) {
      const uint32_t r = root(i);
      if (group[r] == UINT32_MAX) {
        group[r] = r == 0 ? n : static_cast<uint32_t>(s.node_source.size());
        if (r != 0) s.node_source.push_back(n);
      }
      if (group[r] == n) continue;
      for (size_t k = 0; k < 4; ++k)
        if (s.tets[4 * size_t{tets[i]} + k] == n) s.tets[4 * size_t{tets[i]} + k] = group[r];
    }
  }
  // A crossed face opens when its two tets no longer share all three of its nodes.
  auto new_key = [&](uint32_t order) {
    std::array<uint32_t, 3> key;
    for (size_t k = 0; k < 3; ++k) key[k] = s.tets[4 * size_t{order / 4} + kTetFaces[order % 4][k]];
    std::sort(key.begin(), key.end());
    return key;
  };
  for (const SharedFace& f : faces) {
    if (!f.crossed) continue;
    const FaceNodes a = new_key(f.first), b = new_key(f.second);
    if (a != b) {
      ++s.faces_separated;
      s.opened.push_back(f.first);
      s.opened.push_back(f.second);
    } else
      s.crack.push_back(a);
  }
  std::sort(s.crack.begin(), s.crack.end());
  return s;
}

// The tets' shared faces, each marked crossed when the segment between its tets' centroids
// (deformed) passes through a blade triangle; empty with `problem` set when a face has 3 tets.
// `single`: the faces (tet * 4 + local face) used by one tet.
std::vector<SharedFace> crossed_faces(const VolumeMesh& rest, std::span<const double> positions,
                                      const Blade& blade, std::span<const FaceNodes> crack,
                                      std::string& problem, std::vector<uint32_t>& single) {
  const std::vector<TetFace> all = mesh_detail::sorted_tet_faces(rest.tets);
  std::vector<SharedFace> faces;
  for (size_t i = 0; i < all.size();) {
    size_t j = i + 1;
    while (j < all.size() && mesh_detail::same_face(all[j], all[i])) ++j;
    if (j - i > 2) {
      problem = "a face of the mesh is shared by more than two tets";
      return {};
    }
    if (j - i == 1) single.push_back(all[i].order);
    if (j - i == 2)
      faces.push_back({all[i].order, all[i + 1].order,
                       std::binary_search(crack.begin(), crack.end(), all[i].key)});
    i = j;
  }
  std::vector<Vec3> centroid(rest.tet_count());
  for (size_t t = 0; t < rest.tet_count(); ++t) {
    const std::array<Vec3, 4> x = tet_points(positions, &rest.tets[4 * t]);
    centroid[t] = scaled(add(add(x[0], x[1]), add(x[2], x[3])), 0.25);
  }
  for (SharedFace& f : faces) {
    if (f.crossed) continue;  // an earlier stroke's
    const Vec3 &p = centroid[f.first / 4], &q = centroid[f.second / 4];
    Box box = Box::empty();
    box.include(p), box.include(q);
    if (!blade.reach.meets(box, blade.pad)) continue;
    for (const BladeTriangle& triangle : blade.triangles) {
      if (triangle.box.meets(box, blade.pad) &&
          topology_detail::segment_crosses_triangle(p, q, triangle)) {
        f.crossed = true;
        break;
      }
    }
  }
  return faces;
}

// The new mesh from its tets (new node numbers) and node sources: rest positions, boundary,
// edges, and the cut marks of its boundary (exposed by this cut, or marked before). `boundary`:
// the faces used by one new tet when known (else found from the tets).
void build_mesh(const VolumeMesh& rest, std::span<const uint8_t> rest_cut,
                std::vector<uint32_t> tets, TopologyEdit& edit,
                std::optional<std::vector<uint32_t>> boundary = std::nullopt) {
  VolumeMesh& mesh = edit.mesh;
  mesh.dimension = 3;
  mesh.source = rest.source;
  mesh.positions.resize(3 * edit.node_source.size());
  for (size_t n = 0; n < edit.node_source.size(); ++n)
    for (size_t a = 0; a < 3; ++a)
      mesh.positions[3 * n + a] = rest.positions[3 * size_t{edit.node_source[n]} + a];
  mesh.tets = std::move(tets);
  if (boundary)
    mesh_detail::set_boundary(mesh, std::move(*boundary));
  else
    mesh_detail::build_boundary(mesh);
  mesh_detail::build_edges(mesh);
  // Old boundary faces by their node triple, with their mark.
  std::vector<std::pair<std::array<uint32_t, 3>, uint8_t>> old_faces(rest.triangles.size() / 3);
  for (size_t i = 0; i < old_faces.size(); ++i) {
    std::array<uint32_t, 3> key = {rest.triangles[3 * i], rest.triangles[3 * i + 1],
                                   rest.triangles[3 * i + 2]};
    std::sort(key.begin(), key.end());
    old_faces[i] = {key, rest_cut.empty() ? uint8_t{0} : rest_cut[i]};
  }
  std::sort(old_faces.begin(), old_faces.end());
  const size_t count = mesh.triangles.size() / 3;
  edit.cut_triangle.assign(count, 1);  // a face not on the old boundary was inside: exposed
  edit.exposed.assign(count, 1);
  for (size_t i = 0; i < count; ++i) {
    std::array<uint32_t, 3> key;
    for (size_t k = 0; k < 3; ++k) key[k] = edit.node_source[mesh.triangles[3 * i + k]];
    std::sort(key.begin(), key.end());
    const auto at =
        std::lower_bound(old_faces.begin(), old_faces.end(), std::make_pair(key, uint8_t{0}));
    if (at != old_faces.end() && at->first == key) {
      edit.cut_triangle[i] = at->second;
      edit.exposed[i] = 0;
    }
  }
}

}  // namespace

CutResult cut_mesh(const VolumeMesh& rest, std::span<const uint8_t> rest_cut_triangle,
                   std::span<const double> positions, std::span<const double> triangles,
                   CutMode mode, std::span<const FaceNodes> crack) {
  CutResult result;
  result.refused = check_input(rest, rest_cut_triangle, positions, triangles);
  if (!result.refused.empty()) {
    result.edit = unchanged(rest, rest_cut_triangle);
    return result;
  }
  const Blade blade = near_blade(positions, triangles);
  TopologyEdit& edit = result.edit;
  if (mode == CutMode::kRemove) {
    const std::vector<uint8_t> cut = tets_cut(rest, positions, blade);
    const size_t removed = static_cast<size_t>(std::count(cut.begin(), cut.end(), uint8_t{1}));
    if (removed == rest.tet_count()) result.refused = "the cut would remove every tet of the body";
    if (removed == 0 || removed == rest.tet_count()) {
      edit = unchanged(rest, rest_cut_triangle);
      result.crack.assign(crack.begin(), crack.end());
      return result;
    }
    Removal r = remove_tets(rest, cut);
    result.crack = renumbered(crack, r.node_source, rest.node_count());
    edit.node_source = std::move(r.node_source);
    edit.tet_source = std::move(r.tet_source);
    edit.tets_removed = removed;
    edit.nodes_removed = rest.node_count() - edit.node_source.size();
    build_mesh(rest, rest_cut_triangle, std::move(r.tets), edit);
    return result;
  }
  std::vector<uint32_t> single;
  const std::vector<SharedFace> faces =
      crossed_faces(rest, positions, blade, crack, result.refused, single);
  if (!result.refused.empty()) {
    edit = unchanged(rest, rest_cut_triangle);
    return result;
  }
  const bool any =
      std::any_of(faces.begin(), faces.end(), [](const SharedFace& f) { return f.crossed; });
  Separation s = any ? separate(rest, faces) : Separation{};
  result.crack = std::move(s.crack);
  if (s.faces_separated == 0) {
    edit = unchanged(rest, rest_cut_triangle);
    return result;
  }
  edit.node_source = std::move(s.node_source);
  edit.tet_source.resize(rest.tet_count());
  std::iota(edit.tet_source.begin(), edit.tet_source.end(), 0u);
  edit.nodes_added = edit.node_source.size() - rest.node_count();
  edit.faces_separated = s.faces_separated;
  // Splitting nodes joins no faces (a new face maps back to its old one through node_source),
  // so the new boundary is the old one and both sides of every face that opened.
  single.insert(single.end(), s.opened.begin(), s.opened.end());
  build_mesh(rest, rest_cut_triangle, std::move(s.tets), edit, std::move(single));
  return result;
}

}  // namespace tacta
