// cut_embedded_surface: the body's embedded surface carried over one cut, with the faces the cut
// exposed added as triangles of their own.
#include <algorithm>
#include <array>

#include "mesh/geometry.hpp"
#include "mesh/tet_faces.hpp"
#include "tacta/vec3.hpp"
#include "topology/cut_mesh.hpp"

namespace tacta {

namespace {

using Key = std::array<uint32_t, 3>;

Key sorted_key(const uint32_t* v) {
  Key key = {v[0], v[1], v[2]};
  std::sort(key.begin(), key.end());
  return key;
}

bool share_a_node(const std::vector<uint32_t>& tets, uint32_t a, uint32_t b) {
  for (size_t i = 0; i < 4; ++i)
    for (size_t j = 0; j < 4; ++j)
      if (tets[4 * size_t{a} + i] == tets[4 * size_t{b} + j]) return true;
  return false;
}

// Which old triangles survive: their corners' tets remain, and the cut parted none of them.
std::vector<uint8_t> kept_triangles(const EmbeddedSurface& old, const VolumeMesh& old_mesh,
                                    const TopologyEdit& edit,
                                    const std::vector<uint32_t>& new_tet) {
  mesh_detail::NodeUnion pieces_before(old_mesh.node_count()), pieces_now(edit.mesh.node_count());
  pieces_before.join_elements(old_mesh.tets, 4);
  pieces_now.join_elements(edit.mesh.tets, 4);
  // Two tets, old and new index of each, stay together unless they shared a node and share none
  // now, or the cut split the piece that held both.
  auto together = [&](uint32_t old_a, uint32_t old_b, uint32_t a, uint32_t b) {
    if (old_a == old_b) return true;
    if (share_a_node(old_mesh.tets, old_a, old_b) && !share_a_node(edit.mesh.tets, a, b))
      return false;
    return pieces_before.root(old_mesh.tets[4 * size_t{old_a}]) !=
               pieces_before.root(old_mesh.tets[4 * size_t{old_b}]) ||
           pieces_now.root(edit.mesh.tets[4 * size_t{a}]) ==
               pieces_now.root(edit.mesh.tets[4 * size_t{b}]);
  };
  std::vector<uint8_t> kept(old.triangle_count(), 0);
  for (size_t t = 0; t < old.triangle_count(); ++t) {
    std::array<uint32_t, 3> old_tet{}, tet{};
    bool alive = true;
    for (size_t k = 0; k < 3 && alive; ++k) {
      const uint32_t v = old.triangles[3 * t + k];
      alive = v < old.vertex_count() && old.tet[v] < new_tet.size() &&
              new_tet[old.tet[v]] != UINT32_MAX;
      if (alive) old_tet[k] = old.tet[v], tet[k] = new_tet[old.tet[v]];
    }
    kept[t] = alive && together(old_tet[0], old_tet[1], tet[0], tet[1]) &&
              together(old_tet[1], old_tet[2], tet[1], tet[2]) &&
              together(old_tet[2], old_tet[0], tet[2], tet[0]);
  }
  return kept;
}

// Appends vertex (rest position p, tet t, weights w) to s.
void add_vertex(EmbeddedSurface& s, const VolumeMesh& mesh, const Vec3& p, uint32_t t,
                const double* w) {
  s.rest_positions.insert(s.rest_positions.end(), p.begin(), p.end());
  s.tet.push_back(t);
  s.nodes.insert(s.nodes.end(), mesh.tets.begin() + 4 * std::ptrdiff_t{t},
                 mesh.tets.begin() + 4 * std::ptrdiff_t{t} + 4);
  s.weights.insert(s.weights.end(), w, w + 4);
}

}  // namespace

CutSurface cut_embedded_surface(const EmbeddedSurface& old, std::span<const uint8_t> old_cut,
                                const VolumeMesh& old_mesh, const TopologyEdit& edit) {
  const VolumeMesh& mesh = edit.mesh;
  std::vector<uint32_t> new_tet(old_mesh.tet_count(), UINT32_MAX);
  for (uint32_t t = 0; t < edit.tet_source.size(); ++t)
    if (edit.tet_source[t] < new_tet.size() && t < mesh.tet_count())
      new_tet[edit.tet_source[t]] = t;
  const std::vector<uint8_t> kept = kept_triangles(old, old_mesh, edit, new_tet);
  const bool uvs = old.corner_uvs.size() == 6 * old.triangle_count();

  CutSurface out;
  EmbeddedSurface& s = out.surface;
  s.source = old.source;
  std::vector<uint32_t> new_vertex(old.vertex_count(), UINT32_MAX);
  for (size_t t = 0; t < old.triangle_count(); ++t) {
    if (!kept[t]) continue;
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t v = old.triangles[3 * t + k];
      if (new_vertex[v] == UINT32_MAX) new_vertex[v] = 0;
    }
  }
  for (uint32_t v = 0; v < old.vertex_count(); ++v) {
    if (new_vertex[v] == UINT32_MAX) continue;
    new_vertex[v] = static_cast<uint32_t>(s.vertex_count());
    add_vertex(s, mesh, point_at(old.rest_positions.data(), v), new_tet[old.tet[v]],
               &old.weights[4 * size_t{v}]);
  }
  for (size_t t = 0; t < old.triangle_count(); ++t) {
    if (!kept[t]) continue;
    for (size_t k = 0; k < 3; ++k) s.triangles.push_back(new_vertex[old.triangles[3 * t + k]]);
    if (uvs)
      s.corner_uvs.insert(s.corner_uvs.end(), old.corner_uvs.begin() + 6 * std::ptrdiff_t(t),
                          old.corner_uvs.begin() + 6 * std::ptrdiff_t(t) + 6);
    out.cut_triangle.push_back(old_cut.size() == old.triangle_count() ? old_cut[t] : 0);
  }

  // The faces this cut exposed (the edit's `exposed` boundary triangles), bound to their tet.
  const std::vector<mesh_detail::TetFace> faces = mesh_detail::sorted_tet_faces(mesh.tets);
  for (size_t i = 0; i < mesh.triangles.size() / 3; ++i) {
    if (i >= edit.exposed.size() || !edit.exposed[i]) continue;
    const uint32_t* v = &mesh.triangles[3 * i];
    const Key key = sorted_key(v);
    const auto face =
        std::lower_bound(faces.begin(), faces.end(), key,
                         [](const mesh_detail::TetFace& f, const Key& k) { return f.key < k; });
    if (face == faces.end() || face->key != key) continue;  // not a face of the mesh
    const uint32_t t = face->tet();
    for (size_t k = 0; k < 3; ++k) {
      double w[4] = {0, 0, 0, 0};
      for (size_t j = 0; j < 4; ++j) w[j] = mesh.tets[4 * size_t{t} + j] == v[k] ? 1.0 : 0.0;
      s.triangles.push_back(static_cast<uint32_t>(s.vertex_count()));
      add_vertex(s, mesh, point_at(mesh.positions.data(), v[k]), t, w);
    }
    if (uvs) s.corner_uvs.insert(s.corner_uvs.end(), 6, 0.0);
    out.cut_triangle.push_back(1);
  }

  for (size_t v = 0; v < s.vertex_count(); ++v)
    if (*std::min_element(&s.weights[4 * v], &s.weights[4 * v] + 4) < mesh_detail::kInsideWeight)
      ++s.extrapolated_vertices;
  s.positions = s.rest_positions;
  s.normals.assign(s.rest_positions.size(), 0.0);
  update_embedded_surface(s, mesh.positions.data());
  return out;
}

}  // namespace tacta
