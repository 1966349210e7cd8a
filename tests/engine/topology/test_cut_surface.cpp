// The embedded surface carried over a cut: every vertex still gives back its rest position from
// its new tet's rest nodes, no triangle spans pieces the cut parted, and the exposed faces come in
// as marked triangles on the new boundary.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

#include "cut_test_support.hpp"

namespace tacta {
namespace {

// The 4 x 2 x 2 box carrying the boundary of a grid twice as fine over the same box.
VolumeMesh box_with_fine_surface() {
  VolumeMesh mesh = test::box_4x2x2();
  const VolumeMesh fine = make_box_grid({4, 2, 2}, {8, 4, 4}, {0, 0, 0});
  SurfaceMesh surface;
  surface.positions = fine.positions;
  surface.triangles = fine.triangles;
  surface.source = "fine box";
  // Drop the fine grid's interior nodes: only its boundary is the surface.
  std::vector<uint32_t> used(fine.node_count(), UINT32_MAX);
  for (uint32_t n : fine.triangles) used[n] = 0;
  SurfaceMesh compact;
  for (uint32_t n = 0; n < fine.node_count(); ++n)
    if (used[n] == 0) {
      used[n] = static_cast<uint32_t>(compact.positions.size() / 3);
      compact.positions.insert(compact.positions.end(), fine.positions.begin() + 3 * n,
                               fine.positions.begin() + 3 * n + 3);
    }
  for (uint32_t n : fine.triangles) compact.triangles.push_back(used[n]);
  mesh.embedding = bind_surface_to_tets(compact, mesh);
  return mesh;
}

void expect_carried(const CutSurface& cut, const TopologyEdit& edit) {
  const EmbeddedSurface& s = cut.surface;
  const VolumeMesh& mesh = edit.mesh;
  ASSERT_EQ(s.tet.size(), s.vertex_count());
  ASSERT_EQ(s.nodes.size(), 4 * s.vertex_count());
  ASSERT_EQ(s.weights.size(), 4 * s.vertex_count());
  ASSERT_EQ(s.positions.size(), s.rest_positions.size());
  ASSERT_EQ(s.normals.size(), s.rest_positions.size());
  ASSERT_EQ(cut.cut_triangle.size(), s.triangle_count());
  for (size_t v = 0; v < s.vertex_count(); ++v) {
    ASSERT_LT(s.tet[v], mesh.tet_count());
    for (size_t k = 0; k < 4; ++k) EXPECT_EQ(s.nodes[4 * v + k], mesh.tets[4 * s.tet[v] + k]);
    double p[3];
    interpolate_vertex(s, v, mesh.positions.data(), p);
    for (size_t a = 0; a < 3; ++a) EXPECT_NEAR(p[a], s.rest_positions[3 * v + a], 1e-12);
  }
  std::vector<uint8_t> used(s.vertex_count(), 0);
  for (uint32_t v : s.triangles) {
    ASSERT_LT(v, s.vertex_count());
    used[v] = 1;
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0) << "a vertex no triangle uses";
  // No triangle's corners follow different pieces.
  mesh_detail::NodeUnion pieces(mesh.node_count());
  pieces.join_elements(mesh.tets, 4);
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const uint32_t* v = &s.triangles[3 * t];
    const uint32_t piece = pieces.root(s.nodes[4 * v[0]]);
    EXPECT_EQ(pieces.root(s.nodes[4 * v[1]]), piece);
    EXPECT_EQ(pieces.root(s.nodes[4 * v[2]]), piece);
  }
}

TEST(CutSurface, SeparationCarriesTheSurfaceAndClosesTheCut) {
  const VolumeMesh mesh = box_with_fine_surface();
  EmbeddedSurface before = make_embedded_surface(mesh);
  before.corner_uvs.resize(6 * before.triangle_count());
  for (size_t i = 0; i < before.corner_uvs.size(); ++i)
    before.corner_uvs[i] = static_cast<double>(i / 6);
  const CutResult r =
      cut_mesh(mesh, {}, mesh.positions, test::tilted_blade(2.13, 0.1, 0.05), CutMode::kSeparate);
  ASSERT_TRUE(r.edit.changed());
  const CutSurface cut = cut_embedded_surface(before, {}, mesh, r.edit);
  expect_carried(cut, r.edit);
  // The exposed faces, 2 per opened face, are the marked triangles, at their faces' places.
  EXPECT_EQ(test::marked(cut.cut_triangle), 2 * r.edit.faces_separated);
  const size_t kept = cut.surface.triangle_count() - test::marked(cut.cut_triangle);
  EXPECT_LT(kept, before.triangle_count());  // the triangles straddling the cut went
  EXPECT_GT(kept, before.triangle_count() * 3 / 4);
  // Kept triangles keep their texture coordinates, in their old order; cut faces get zeros.
  ASSERT_EQ(cut.surface.corner_uvs.size(), 6 * cut.surface.triangle_count());
  for (size_t t = 1; t < kept; ++t)
    EXPECT_LT(cut.surface.corner_uvs[6 * (t - 1)], cut.surface.corner_uvs[6 * t]);
  for (size_t i = 6 * kept; i < cut.surface.corner_uvs.size(); ++i)
    EXPECT_EQ(cut.surface.corner_uvs[i], 0.0);
  for (size_t t = 0; t < cut.surface.triangle_count(); ++t) {
    if (!cut.cut_triangle[t]) {
      ASSERT_LT(t, kept) << "kept triangles come first";
      continue;
    }
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t v = cut.surface.triangles[3 * t + k];
      const double* w = &cut.surface.weights[4 * v];
      EXPECT_EQ(std::count(w, w + 4, 1.0), 1);
      EXPECT_EQ(std::count(w, w + 4, 0.0), 3);
    }
  }
  // Every exposed boundary triangle of the mesh appears once in the surface (by rest position).
  std::vector<std::array<double, 9>> faces, drawn;
  for (size_t i = 0; i < r.edit.cut_triangle.size(); ++i) {
    if (!r.edit.cut_triangle[i]) continue;
    std::array<double, 9> f;
    for (size_t k = 0; k < 3; ++k)
      for (size_t a = 0; a < 3; ++a)
        f[3 * k + a] = r.edit.mesh.positions[3 * r.edit.mesh.triangles[3 * i + k] + a];
    faces.push_back(f);
  }
  for (size_t t = kept; t < cut.surface.triangle_count(); ++t) {
    std::array<double, 9> f;
    for (size_t k = 0; k < 3; ++k)
      for (size_t a = 0; a < 3; ++a)
        f[3 * k + a] = cut.surface.rest_positions[3 * cut.surface.triangles[3 * t + k] + a];
    drawn.push_back(f);
  }
  std::sort(faces.begin(), faces.end());
  std::sort(drawn.begin(), drawn.end());
  EXPECT_EQ(faces, drawn);
}

TEST(CutSurface, RemovalDropsTheVerticesOfRemovedTets) {
  const VolumeMesh mesh = box_with_fine_surface();
  const EmbeddedSurface before = make_embedded_surface(mesh);
  const CutResult r =
      cut_mesh(mesh, {}, mesh.positions, test::tilted_blade(2.13, 0.1, 0.05), CutMode::kRemove);
  ASSERT_TRUE(r.edit.changed());
  const CutSurface cut = cut_embedded_surface(before, {}, mesh, r.edit);
  expect_carried(cut, r.edit);
  EXPECT_EQ(test::marked(cut.cut_triangle), test::marked(r.edit.cut_triangle));
  EXPECT_LT(cut.surface.vertex_count() - 3 * test::marked(cut.cut_triangle), before.vertex_count());
  // A second cut elsewhere keeps the first one's triangles and marks.
  const CutResult again = cut_mesh(r.edit.mesh, r.edit.cut_triangle, r.edit.mesh.positions,
                                   test::tilted_blade(0.6, 0, 0), CutMode::kSeparate);
  ASSERT_TRUE(again.edit.changed());
  const CutSurface second =
      cut_embedded_surface(cut.surface, cut.cut_triangle, r.edit.mesh, again.edit);
  expect_carried(second, again.edit);
  EXPECT_EQ(test::marked(second.cut_triangle),
            test::marked(cut.cut_triangle) + 2 * again.edit.faces_separated);
}

TEST(CutSurface, AnUnchangedEditKeepsTheSurface) {
  const VolumeMesh mesh = box_with_fine_surface();
  const EmbeddedSurface before = make_embedded_surface(mesh);
  const CutResult r =
      cut_mesh(mesh, {}, mesh.positions, test::tilted_blade(9, 0, 0), CutMode::kSeparate);
  ASSERT_FALSE(r.edit.changed());
  const CutSurface cut = cut_embedded_surface(before, {}, mesh, r.edit);
  EXPECT_EQ(cut.surface.triangles, before.triangles);
  EXPECT_EQ(cut.surface.rest_positions, before.rest_positions);
  EXPECT_EQ(cut.surface.tet, before.tet);
  EXPECT_EQ(test::marked(cut.cut_triangle), 0u);
}

}  // namespace
}  // namespace tacta
