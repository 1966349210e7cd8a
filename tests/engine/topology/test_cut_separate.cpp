// Separation: the faces a blade crosses open, nodes on them are copied, nothing else changes;
// checked against the faces found here from the tets' centroids, the pieces the body falls into
// and its volume.
#include <algorithm>
#include <gtest/gtest.h>
#include <map>

#include "cut_test_support.hpp"

namespace tacta {
namespace {

using test::box_4x2x2;
using test::tilted_blade;

// Interior faces whose two tets have centroids on opposite sides of x = x0 + sy y + sz z.
size_t faces_across_plane(const VolumeMesh& mesh, double x0, double sy, double sz) {
  std::map<std::array<uint32_t, 3>, std::vector<size_t>> tets_of_face;
  static constexpr int kOpposite[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  for (size_t t = 0; t < mesh.tet_count(); ++t)
    for (const auto& f : kOpposite) {
      std::array<uint32_t, 3> key;
      for (size_t k = 0; k < 3; ++k) key[k] = mesh.tets[4 * t + static_cast<size_t>(f[k])];
      std::sort(key.begin(), key.end());
      tets_of_face[key].push_back(t);
    }
  auto side = [&](size_t t) {
    Vec3 c{0, 0, 0};
    for (size_t k = 0; k < 4; ++k)
      c = add_scaled(c, point_at(mesh.positions.data(), mesh.tets[4 * t + k]), 0.25);
    return c[0] - (x0 + sy * c[1] + sz * c[2]) > 0;
  };
  size_t count = 0;
  for (const auto& [key, tets] : tets_of_face)
    if (tets.size() == 2 && side(tets[0]) != side(tets[1])) ++count;
  return count;
}

void expect_kept_mass_and_tets(const VolumeMesh& mesh, const TopologyEdit& e) {
  EXPECT_EQ(e.mesh.tet_count(), mesh.tet_count());
  EXPECT_EQ(e.tets_removed, 0u);
  EXPECT_EQ(e.nodes_removed, 0u);
  for (size_t t = 0; t < e.tet_source.size(); ++t) EXPECT_EQ(e.tet_source[t], t);
  // Each tet keeps its nodes, or copies of them, in its own order.
  for (size_t i = 0; i < mesh.tets.size(); ++i)
    EXPECT_EQ(e.node_source[e.mesh.tets[i]], mesh.tets[i]);
  EXPECT_EQ(e.mesh.node_count(), mesh.node_count() + e.nodes_added);
  EXPECT_NEAR(test::volume(e.mesh), test::volume(mesh), 1e-12 * test::volume(mesh));
  const std::vector<std::string> problems = topology_problems(e.mesh);
  EXPECT_TRUE(problems.empty()) << problems[0];
}

void expect_split_in_two(const VolumeMesh& mesh, const std::vector<double>& blade, size_t faces) {
  ASSERT_GT(faces, 0u);
  const CutResult r = cut_mesh(mesh, {}, mesh.positions, blade, CutMode::kSeparate);
  ASSERT_TRUE(r.refused.empty()) << r.refused;
  const TopologyEdit& e = r.edit;
  EXPECT_TRUE(e.changed());
  EXPECT_EQ(e.faces_separated, faces);
  EXPECT_GT(e.nodes_added, 0u);
  EXPECT_EQ(test::pieces(e.mesh), 2u);
  // Both sides of every opened face are new boundary, and marked.
  EXPECT_EQ(test::marked(e.cut_triangle), 2 * faces);
  EXPECT_EQ(e.mesh.triangles.size() / 3, mesh.triangles.size() / 3 + 2 * faces);
  expect_kept_mass_and_tets(mesh, e);
}

TEST(CutSeparate, ATiltedPlaneOpensExactlyTheFacesBetweenTheHalves) {
  const VolumeMesh mesh = box_4x2x2();
  expect_split_in_two(mesh, tilted_blade(2.13, 0.1, 0.05),
                      faces_across_plane(mesh, 2.13, 0.1, 0.05));
}

TEST(CutSeparate, ABladeOnAGridPlaneSplitsAlongIt) {
  const VolumeMesh mesh = box_4x2x2();
  // x = 2: the 2 x 2 unit squares there, 2 triangles each; no centroid lies on the plane.
  expect_split_in_two(mesh, tilted_blade(2, 0, 0), 8);
  EXPECT_EQ(faces_across_plane(mesh, 2, 0, 0), 8u);
}

TEST(CutSeparate, APlaneThroughNodesSplitsTheBoxOrSphereInTwo) {
  const VolumeMesh box = box_4x2x2();
  expect_split_in_two(box, tilted_blade(1, 1, 0), faces_across_plane(box, 1, 1, 0));
  const VolumeMesh sphere = make_sphere(1.0, {0, 0, 0}, 1);
  expect_split_in_two(sphere, tilted_blade(0.0123, 0.21, -0.07),
                      faces_across_plane(sphere, 0.0123, 0.21, -0.07));
}

TEST(CutSeparate, APartialBladeOpensACrackAndTheBodyStaysOnePiece) {
  const VolumeMesh mesh = box_4x2x2();
  // The plane x = 2.13 + ... over y < 1.2 only: a crack from the y = 0 face into the body.
  const CutResult r = cut_mesh(mesh, {}, mesh.positions, tilted_blade(2.13, 0.1, 0.05, -5, 1.2),
                               CutMode::kSeparate);
  ASSERT_TRUE(r.refused.empty());
  EXPECT_TRUE(r.edit.changed());
  EXPECT_GT(r.edit.nodes_added, 0u);
  EXPECT_GT(r.edit.faces_separated, 0u);
  EXPECT_LT(r.edit.faces_separated, faces_across_plane(mesh, 2.13, 0.1, 0.05));
  EXPECT_EQ(test::pieces(r.edit.mesh), 1u);
  expect_kept_mass_and_tets(mesh, r.edit);
  // Closing the crack with the rest of the plane splits the body.
  const CutResult rest = cut_mesh(r.edit.mesh, r.edit.cut_triangle, r.edit.mesh.positions,
                                  tilted_blade(2.13, 0.1, 0.05, 1.0, 5), CutMode::kSeparate);
  EXPECT_TRUE(rest.edit.changed());
  EXPECT_EQ(test::pieces(rest.edit.mesh), 2u);
  EXPECT_TRUE(topology_problems(rest.edit.mesh).empty());
}

TEST(CutSeparate, AnInteriorCrackThatCannotOpenChangesNothing) {
  const VolumeMesh mesh = make_box_grid({4, 4, 4}, {4, 4, 4}, {0, 0, 0});
  // A blade 0.04 m across, across the segment between the centroids of two tets sharing a face deep
  // inside: that one face is crossed, but around each of its nodes the two tets still hold
  // together through the other faces, so nothing can open. (Removal takes the tets it is in.)
  auto centroid = [&](size_t t) {
    Vec3 c{0, 0, 0};
    for (size_t k = 0; k < 4; ++k)
      c = add_scaled(c, point_at(mesh.positions.data(), mesh.tets[4 * t + k]), 0.25);
    return c;
  };
  size_t a = 0;
  while (distance(centroid(a), {1.5, 1.5, 1.5}) > 0.5) ++a;
  size_t b = 0;
  for (; b < mesh.tet_count(); ++b) {
    size_t shared = 0;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = 0; j < 4; ++j) shared += mesh.tets[4 * a + i] == mesh.tets[4 * b + j];
    if (b != a && shared == 3) break;
  }
  ASSERT_LT(b, mesh.tet_count());
  const Vec3 d = normalized(sub(centroid(b), centroid(a)));
  const Vec3 u = scaled(normalized(cross(d, {0.3, 0.5, 0.7})), 0.02);
  const Vec3 v = cross(d, u);
  const Vec3 m = add_scaled(centroid(a), sub(centroid(b), centroid(a)), 0.6);  // inside b
  const std::vector<double> blade =
      test::quad_blade(sub(sub(m, u), v), sub(add(m, u), v), add(add(m, u), v), add(sub(m, u), v));
  const CutResult r = cut_mesh(mesh, {}, mesh.positions, blade, CutMode::kSeparate);
  EXPECT_TRUE(r.refused.empty());
  EXPECT_FALSE(r.edit.changed());
  EXPECT_EQ(r.edit.nodes_added, 0u);
  EXPECT_TRUE(cut_mesh(mesh, {}, mesh.positions, blade, CutMode::kRemove).edit.changed());
}

TEST(CutSeparate, ARepeatedCutAndACutInsideAnOpenedGapChangeNothing) {
  const VolumeMesh mesh = box_4x2x2();
  const std::vector<double> blade = tilted_blade(2.13, 0.1, 0.05);
  const CutResult first = cut_mesh(mesh, {}, mesh.positions, blade, CutMode::kSeparate);
  ASSERT_TRUE(first.edit.changed());
  const TopologyEdit& e = first.edit;
  for (const std::vector<double>& again :
       {blade, tilted_blade(2.13, 0.1, 0.05, 0.2, 0.8, 0.2, 0.8)}) {
    const CutResult r =
        cut_mesh(e.mesh, e.cut_triangle, e.mesh.positions, again, CutMode::kSeparate);
    EXPECT_TRUE(r.refused.empty());
    EXPECT_FALSE(r.edit.changed());
    EXPECT_EQ(r.edit.mesh.tets, e.mesh.tets);
    EXPECT_EQ(r.edit.cut_triangle, e.cut_triangle);
  }
}

TEST(CutSeparate, EarlierCutFacesStayMarked) {
  const VolumeMesh mesh = box_4x2x2();
  const CutResult first =
      cut_mesh(mesh, {}, mesh.positions, tilted_blade(1, 0, 0), CutMode::kSeparate);
  ASSERT_EQ(first.edit.faces_separated, 8u);
  const TopologyEdit& e = first.edit;
  const CutResult second =
      cut_mesh(e.mesh, e.cut_triangle, e.mesh.positions, tilted_blade(3, 0, 0), CutMode::kSeparate);
  ASSERT_EQ(second.edit.faces_separated, 8u);
  EXPECT_EQ(test::pieces(second.edit.mesh), 3u);
  EXPECT_EQ(test::marked(second.edit.cut_triangle), 32u);
  // Without the first cut's marks only the second cut's faces are marked.
  const CutResult unmarked =
      cut_mesh(e.mesh, {}, e.mesh.positions, tilted_blade(3, 0, 0), CutMode::kSeparate);
  EXPECT_EQ(test::marked(unmarked.edit.cut_triangle), 16u);
  // A removal next to the first cut keeps its marks too.
  const CutResult removal =
      cut_mesh(e.mesh, e.cut_triangle, e.mesh.positions, tilted_blade(3.5, 0, 0), CutMode::kRemove);
  ASSERT_TRUE(removal.edit.changed());
  size_t first_cut_faces = 0;
  for (size_t i = 0; i < removal.edit.mesh.triangles.size() / 3; ++i) {
    bool on_x1 = true;
    for (size_t k = 0; k < 3; ++k)
      on_x1 =
          on_x1 && removal.edit.mesh.positions[3 * removal.edit.mesh.triangles[3 * i + k]] == 1.0;
    if (on_x1) {
      EXPECT_EQ(removal.edit.cut_triangle[i], 1);
      ++first_cut_faces;
    }
  }
  EXPECT_EQ(first_cut_faces, 16u);
}

TEST(CutSeparate, DeformedNodesPlaceTheBlade) {
  const VolumeMesh mesh = box_4x2x2();
  // Squash the body to half its length in x: the blade at x = 1.065 is the rest x = 2.13.
  std::vector<double> squashed = mesh.positions;
  for (size_t n = 0; n < mesh.node_count(); ++n) squashed[3 * n] *= 0.5;
  const CutResult r =
      cut_mesh(mesh, {}, squashed, tilted_blade(1.065, 0.05, 0.025), CutMode::kSeparate);
  EXPECT_EQ(r.edit.faces_separated, faces_across_plane(mesh, 2.13, 0.1, 0.05));
  EXPECT_EQ(test::pieces(r.edit.mesh), 2u);
  // The new mesh is at rest: positions of the sources, not of the squashed nodes.
  for (size_t n = 0; n < r.edit.node_source.size(); ++n)
    EXPECT_EQ(r.edit.mesh.positions[3 * n], mesh.positions[3 * r.edit.node_source[n]]);
}

}  // namespace
}  // namespace tacta

namespace tacta {
namespace {

// An incision in strokes (a device's blade is cut every few ms): a slit in the grid plane x = 2
// of an 8 x 8 x 8 box, z in [1, 3] (clear of the box's faces), drawn as 40 strips of y. A strip
// alone severs no node's tets (an interior node on the plane is severed only once every face
// around it is crossed), so its faces stay closed; carried over as the crack, they open once the
// strips around them are drawn. The strokes end as the whole slit cut at once would.
TEST(CutSeparate, AnIncisionInStrokesOpensAsOneCutWould) {
  const VolumeMesh box = make_box_grid({4, 4, 4}, {8, 8, 8}, {0, 0, 0});
  auto strokes = [&](bool remember, size_t& opened) {
    VolumeMesh mesh = box;
    std::vector<uint8_t> marks;
    std::vector<FaceNodes> crack;
    opened = 0;
    for (int k = 0; k < 40; ++k) {
      const double y0 = -0.5 + 0.125 * k, y1 = y0 + 0.125;
      const CutResult r =
          cut_mesh(mesh, marks, mesh.positions, test::tilted_blade(2, 0, 0, y0, y1, 1, 3),
                   CutMode::kSeparate, crack);
      EXPECT_TRUE(r.refused.empty()) << r.refused;
      EXPECT_TRUE(std::is_sorted(r.crack.begin(), r.crack.end()));
      if (remember) crack = r.crack;
      if (!r.edit.changed()) continue;
      opened += r.edit.faces_separated;
      mesh = r.edit.mesh;
      marks = r.edit.cut_triangle;
    }
    EXPECT_TRUE(topology_problems(mesh).empty());
    return mesh;
  };
  const CutResult once = cut_mesh(box, {}, box.positions, test::tilted_blade(2, 0, 0, -1, 5, 1, 3),
                                  CutMode::kSeparate);
  ASSERT_GT(once.edit.faces_separated, 0u);
  size_t opened = 0;
  const VolumeMesh cut = strokes(true, opened);
  EXPECT_EQ(opened, once.edit.faces_separated);
  EXPECT_EQ(cut.node_count(), once.edit.mesh.node_count());
  size_t opened_without = 0;  // the same strokes, each forgetting the last
  strokes(false, opened_without);
  EXPECT_LT(opened_without, opened);
}

}  // namespace
}  // namespace tacta
