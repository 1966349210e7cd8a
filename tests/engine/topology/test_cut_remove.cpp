// Removal (carving): the tets a blade passes through go, and only those; the counts, sources,
// marks and volume of the result are checked against numbers found here from the nodes' sides.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

#include "cut_test_support.hpp"

namespace tacta {
namespace {

using test::box_4x2x2;
using test::tilted_blade;

// Tets with nodes strictly on both sides of the plane x = x0 + sy y + sz z: the ones it crosses.
std::vector<uint8_t> crossed_by_plane(const VolumeMesh& mesh, double x0, double sy, double sz) {
  std::vector<uint8_t> crossed(mesh.tet_count(), 0);
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    bool below = false, above = false;
    for (size_t k = 0; k < 4; ++k) {
      const Vec3 p = point_at(mesh.positions.data(), mesh.tets[4 * t + k]);
      const double side = p[0] - (x0 + sy * p[1] + sz * p[2]);
      below = below || side < 0, above = above || side > 0;
    }
    crossed[t] = below && above;
  }
  return crossed;
}

void expect_removed_exactly(const VolumeMesh& mesh, const std::vector<double>& positions,
                            const std::vector<double>& blade, const std::vector<uint8_t>& crossed) {
  const CutResult r = cut_mesh(mesh, {}, positions, blade, CutMode::kRemove);
  ASSERT_TRUE(r.refused.empty()) << r.refused;
  const TopologyEdit& e = r.edit;
  const size_t expected = test::marked(crossed);
  ASSERT_GT(expected, 0u);
  EXPECT_TRUE(e.changed());
  EXPECT_EQ(e.tets_removed, expected);
  EXPECT_EQ(e.mesh.tet_count(), mesh.tet_count() - expected);
  double removed_volume = 0;
  for (size_t t = 0; t < mesh.tet_count(); ++t)
    if (crossed[t]) removed_volume += test::tet_volume(mesh, t);
  // Kept tets are the uncrossed ones, in order, with their own nodes' rest positions.
  ASSERT_EQ(e.tet_source.size(), e.mesh.tet_count());
  size_t next = 0;
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    if (crossed[t]) continue;
    ASSERT_EQ(e.tet_source[next], t);
    for (size_t k = 0; k < 4; ++k)
      EXPECT_EQ(e.node_source[e.mesh.tets[4 * next + k]], mesh.tets[4 * t + k]);
    ++next;
  }
  for (size_t n = 0; n < e.node_source.size(); ++n)
    for (size_t a = 0; a < 3; ++a)
      EXPECT_EQ(e.mesh.positions[3 * n + a], mesh.positions[3 * e.node_source[n] + a]);
  EXPECT_EQ(e.nodes_removed, mesh.node_count() - e.mesh.node_count());
  EXPECT_NEAR(test::volume(e.mesh), test::volume(mesh) - removed_volume,
              1e-12 * test::volume(mesh));
  EXPECT_TRUE(topology_problems(e.mesh).empty()) << topology_problems(e.mesh)[0];
  // Exposed faces: boundary faces now that were no boundary face before (by source nodes).
  EXPECT_GT(test::marked(e.cut_triangle), 0u);
  EXPECT_EQ(e.cut_triangle.size(), e.mesh.triangles.size() / 3);
}

TEST(CutRemove, ATiltedPlaneTakesExactlyTheTetsItCrosses) {
  const VolumeMesh mesh = box_4x2x2();
  // x = 2.13 + 0.1 y + 0.05 z passes through no node of the unit grid.
  expect_removed_exactly(mesh, mesh.positions, tilted_blade(2.13, 0.1, 0.05),
                         crossed_by_plane(mesh, 2.13, 0.1, 0.05));
}

TEST(CutRemove, APlaneThroughNodesTakesOnlyTheTetsWithNodesOnBothSides) {
  const VolumeMesh mesh = box_4x2x2();
  // x = 1 + y passes through grid nodes and along tet edges and faces.
  expect_removed_exactly(mesh, mesh.positions, tilted_blade(1, 1, 0),
                         crossed_by_plane(mesh, 1, 1, 0));
}

TEST(CutRemove, TheBladeIsPlacedAgainstTheDeformedNodes) {
  const VolumeMesh mesh = box_4x2x2();
  // The body shifted by 10 m along x: the blade at x = 12.13 meets what the rest x = 2.13 would.
  std::vector<double> moved = mesh.positions;
  for (size_t n = 0; n < mesh.node_count(); ++n) moved[3 * n] += 10;
  expect_removed_exactly(mesh, moved, tilted_blade(12.13, 0.1, 0.05),
                         crossed_by_plane(mesh, 2.13, 0.1, 0.05));
  // And the rest-frame blade, now beside the body, misses it.
  EXPECT_FALSE(
      cut_mesh(mesh, {}, moved, tilted_blade(2.13, 0.1, 0.05), CutMode::kRemove).edit.changed());
}

TEST(CutRemove, TheSphereLosesTheTetsAPlaneCrosses) {
  const VolumeMesh mesh = make_sphere(1.0, {0, 0, 0}, 1);
  expect_removed_exactly(mesh, mesh.positions, tilted_blade(0.0123, 0.21, -0.07),
                         crossed_by_plane(mesh, 0.0123, 0.21, -0.07));
}

TEST(CutRemove, ABladeOnAGridFacePlaneOrMissingTheBodyRemovesNothing) {
  const VolumeMesh mesh = box_4x2x2();
  for (const std::vector<double>& blade :
       {tilted_blade(2, 0, 0), tilted_blade(0, 0, 0), tilted_blade(4, 0, 0),
        tilted_blade(7, 0.1, 0.05), tilted_blade(2.5, 0, 0, 3, 5)}) {
    const CutResult r = cut_mesh(mesh, {}, mesh.positions, blade, CutMode::kRemove);
    EXPECT_TRUE(r.refused.empty());
    EXPECT_FALSE(r.edit.changed());
    EXPECT_EQ(r.edit.mesh.tets, mesh.tets);
    EXPECT_TRUE(topology_problems(r.edit.mesh).empty());
  }
}

TEST(CutRemove, ASecondCutOnTheSamePlaneFindsNothingLeft) {
  const VolumeMesh mesh = box_4x2x2();
  const std::vector<double> blade = tilted_blade(2.13, 0.1, 0.05);
  const CutResult first = cut_mesh(mesh, {}, mesh.positions, blade, CutMode::kRemove);
  ASSERT_TRUE(first.edit.changed());
  const CutResult second = cut_mesh(first.edit.mesh, first.edit.cut_triangle,
                                    first.edit.mesh.positions, blade, CutMode::kRemove);
  EXPECT_FALSE(second.edit.changed());
  EXPECT_EQ(second.edit.cut_triangle, first.edit.cut_triangle);
}

TEST(CutRemove, ACutThatWouldTakeEveryTetIsRefused) {
  // One cube: every one of its 6 tets holds the diagonal (0,0,0)-(1,1,1), which the plane
  // x + y + z = 1.5 cuts in the middle.
  const VolumeMesh cube = make_box_grid({1, 1, 1}, {1, 1, 1}, {0, 0, 0});
  auto at = [](double y, double z) { return Vec3{1.5 - y - z, y, z}; };
  const std::vector<double> blade = test::quad_blade(at(-9, -9), at(9, -9), at(9, 9), at(-9, 9));
  const CutResult r = cut_mesh(cube, {}, cube.positions, blade, CutMode::kRemove);
  EXPECT_NE(r.refused.find("every tet"), std::string::npos) << r.refused;
  EXPECT_FALSE(r.edit.changed());
  EXPECT_EQ(r.edit.mesh.tets, cube.tets);
  // Separation keeps every tet, so the same blade may split the cube.
  EXPECT_TRUE(cut_mesh(cube, {}, cube.positions, blade, CutMode::kSeparate).refused.empty());
}

TEST(CutRemove, BadInputIsRefusedNotACrash) {
  const VolumeMesh mesh = box_4x2x2();
  const std::vector<double> blade = tilted_blade(2.13, 0.1, 0.05);
  std::vector<double> short_positions(mesh.positions.begin(), mesh.positions.end() - 3);
  EXPECT_FALSE(cut_mesh(mesh, {}, short_positions, blade, CutMode::kRemove).refused.empty());
  std::vector<double> ragged(blade.begin(), blade.end() - 1);
  EXPECT_FALSE(cut_mesh(mesh, {}, mesh.positions, ragged, CutMode::kRemove).refused.empty());
  const std::vector<uint8_t> marks(3, 0);
  EXPECT_FALSE(cut_mesh(mesh, marks, mesh.positions, blade, CutMode::kSeparate).refused.empty());
  std::vector<double> lost = mesh.positions;
  lost[7] = std::nan("");
  const CutResult nan_node = cut_mesh(mesh, {}, lost, blade, CutMode::kRemove);
  EXPECT_NE(nan_node.refused.find("node 2"), std::string::npos) << nan_node.refused;
  EXPECT_EQ(nan_node.edit.mesh.tets, mesh.tets);
  // A flat or non-finite blade triangle cuts nothing.
  std::vector<double> flat = {1.5, 0, 0, 1.5, 2, 2, 1.5, 1, 1};
  EXPECT_FALSE(cut_mesh(mesh, {}, mesh.positions, flat, CutMode::kRemove).edit.changed());
  std::vector<double> nan = blade;
  for (size_t i = 0; i < nan.size(); i += 4) nan[i] = std::nan("");
  EXPECT_FALSE(cut_mesh(mesh, {}, mesh.positions, nan, CutMode::kRemove).edit.changed());
}

TEST(CutMode, NamesParseBack) {
  for (CutMode m : {CutMode::kRemove, CutMode::kSeparate}) {
    CutMode parsed = m == CutMode::kRemove ? CutMode::kSeparate : CutMode::kRemove;
    ASSERT_TRUE(parse_cut_mode(cut_mode_name(m), parsed));
    EXPECT_EQ(parsed, m);
  }
  CutMode m = CutMode::kRemove;
  EXPECT_FALSE(parse_cut_mode("Separate", m));
  EXPECT_FALSE(parse_cut_mode("", m));
  EXPECT_STREQ(cut_mode_name(CutMode::kSeparate), "separate");
}

}  // namespace
}  // namespace tacta
