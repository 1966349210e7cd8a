// Built-in bodies: volumes, node order, conformity, lumped masses, load_body_mesh dispatch.
#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <set>

#include "mesh_test_support.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {
namespace {

TEST(Primitives, BoxGridVolumeAndNodeOrder) {
  VolumeMesh box = make_box_grid({0.3, 0.2, 0.5}, {3, 2, 4}, {1, -1, 2});
  EXPECT_EQ(box.node_count(), 4u * 3u * 5u);
  EXPECT_EQ(box.tet_count(), 6u * 3u * 2u * 4u);
  EXPECT_NEAR(test::total_volume(box), 0.3 * 0.2 * 0.5, 1e-12 * 0.03);
  // index = i + (nx+1) (j + (ny+1) k): node (1, 2, 3) sits at origin + (0.1, 0.2, 0.375).
  const size_t n = 1 + 4 * (2 + 3 * 3);
  EXPECT_NEAR(box.positions[3 * n], 1.1, 1e-15);
  EXPECT_NEAR(box.positions[3 * n + 1], -0.8, 1e-15);
  EXPECT_NEAR(box.positions[3 * n + 2], 2.375, 1e-15);
  // Conforming: the boundary is exactly the box surface, 2 triangles per boundary cell face.
  EXPECT_EQ(box.triangles.size() / 3, 2u * 2u * (3u * 2u + 2u * 4u + 3u * 4u));
  LoadReport closedness;
  check_closed(test::boundary_of(box), closedness);
  EXPECT_TRUE(closedness.closed());
  EXPECT_NEAR(enclosed_volume(test::boundary_of(box)), 0.03, 1e-15);
}

TEST(Primitives, BeamGridMatchesSofaCantileverCounts) {
  // SOFA's cantilever validation: 5 x 5 x 30 nodes over 0.02 x 0.02 x 0.2 m.
  VolumeMesh beam = make_beam_grid({0.02, 0.02, 0.2}, {4, 4, 29}, {0, 0, 0});
  EXPECT_EQ(beam.node_count(), 750u);
  EXPECT_NEAR(test::total_volume(beam), 0.02 * 0.02 * 0.2, 1e-12 * 8e-5);
  EXPECT_EQ(beam.source, "beam_grid");
}

// The symmetric split: reflecting the grid through its mid-plane (x = size/2 with an even cell
// count) maps every tet onto a tet of the grid, so a load in that plane bends it in that plane.
TEST(Primitives, BeamGridSplitIsMirrorSymmetric) {
  const std::array<int, 3> cells = {4, 4, 29};
  VolumeMesh beam = make_beam_grid({0.02, 0.02, 0.2}, cells, {0, 0, 0});
  auto reflected = [&](uint32_t node) {  // node (i, j, k) -> (nx - i, j, k)
    const uint32_t nx = static_cast<uint32_t>(cells[0]) + 1;
    return (nx - 1 - node % nx) + nx * (node / nx);
  };
  std::set<std::array<uint32_t, 4>> tets;
  for (size_t t = 0; t < beam.tet_count(); ++t) {
    std::array<uint32_t, 4> tet{beam.tets[4 * t], beam.tets[4 * t + 1], beam.tets[4 * t + 2],
                                beam.tets[4 * t + 3]};
    std::sort(tet.begin(), tet.end());
    tets.insert(tet);
  }
  for (size_t t = 0; t < beam.tet_count(); ++t) {
    std::array<uint32_t, 4> image{};
    for (size_t c = 0; c < 4; ++c) image[c] = reflected(beam.tets[4 * t + c]);
    std::sort(image.begin(), image.end());
    ASSERT_TRUE(tets.count(image)) << "tet " << t << " has no mirror image";
  }
  LoadReport closedness;
  check_closed(test::boundary_of(beam), closedness);
  EXPECT_TRUE(closedness.closed());
  EXPECT_EQ(beam.triangles.size() / 3, 2u * 2u * (4u * 4u + 2u * 4u * 29u));  // conforming
  EXPECT_GT(mesh_quality(beam).min_volume, 0.0);
}

TEST(Primitives, UnitSquareNodeOrder) {
  VolumeMesh square = make_quad_grid({1, 1, 0}, {1, 1, 1}, {0, 0, 0});
  EXPECT_EQ(square.dimension, 2u);
  ASSERT_EQ(square.node_count(), 4u);
  const double expected[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};  // SW, SE, NW, NE
  for (size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(square.positions[3 * i], expected[i][0]);
    EXPECT_EQ(square.positions[3 * i + 1], expected[i][1]);
    EXPECT_EQ(square.positions[3 * i + 2], 0.0);
  }
  EXPECT_EQ(square.quads, (std::vector<uint32_t>{0, 1, 3, 2}));
  EXPECT_EQ(square.triangles, (std::vector<uint32_t>{0, 1, 3, 0, 3, 2}));
  EXPECT_EQ(square.edges, (std::vector<uint32_t>{0, 1, 0, 2, 1, 3, 2, 3}));
  std::vector<double> m = lumped_masses(square, 2.0);  // kg/m^3 over 1 m^2, unit thickness
  for (double mass : m) EXPECT_DOUBLE_EQ(mass, 0.5);
}

TEST(Primitives, QuadGridMasses) {
  VolumeMesh grid = make_quad_grid({2, 1, 0}, {4, 2, 1}, {0, 0, 0});
  EXPECT_EQ(grid.quads.size() / 4, 8u);
  EXPECT_EQ(grid.edges.size() / 2, 4u * 3u + 5u * 2u);
  std::vector<double> m = lumped_masses(grid, 3.0);
  EXPECT_NEAR(m[0], 3.0 * 0.25 / 4, 1e-15);  // corner: one quad
  EXPECT_NEAR(m[6], 3.0 * 0.25, 1e-15);      // interior node (1, 1): four quads
  EXPECT_NEAR(test::total_volume(grid), 2.0, 1e-14);
}

TEST(Primitives, TetMassesSumToDensityTimesVolume) {
  VolumeMesh box = make_box_grid({1, 2, 3}, {2, 2, 2}, {0, 0, 0});
  std::vector<double> m = lumped_masses(box, 1000.0);
  double total = 0;
  for (double mass : m) {
    EXPECT_GT(mass, 0.0);
    total += mass;
  }
  EXPECT_NEAR(total, 6000.0, 1e-9);
}

TEST(Primitives, SphereVolumeAndRadius) {
  const double r = 0.05;
  for (int subdivisions = 1; subdivisions <= 3; ++subdivisions) {
    VolumeMesh ball = make_sphere(r, {0.1, 0.2, 0.3}, subdivisions);
    const double exact = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    const double tolerance = subdivisions == 1 ? 0.15 : 0.04;
    EXPECT_NEAR(test::total_volume(ball), exact, tolerance * exact) << subdivisions;
    for (size_t i = 0; i < ball.node_count(); ++i) {
      double dx = ball.positions[3 * i] - 0.1, dy = ball.positions[3 * i + 1] - 0.2,
             dz = ball.positions[3 * i + 2] - 0.3;
      EXPECT_LE(std::sqrt(dx * dx + dy * dy + dz * dz), r * (1 + 1e-12));
    }
  }
}

TEST(Primitives, SphereHasNoInvertedTets) {
  // The radial map must keep every tet of the cube grid positive: re-finalizing flips none.
  for (int subdivisions = 0; subdivisions <= 3; ++subdivisions) {
    VolumeMesh ball = make_sphere(1.0, {0, 0, 0}, subdivisions);
    LoadReport report;
    finalize(ball, &report);
    EXPECT_EQ(report.inverted_tets, 0u);
    MeshQuality q = mesh_quality(ball);
    EXPECT_GT(q.min_volume, 0.0);
    EXPECT_LT(q.worst_aspect_ratio, 3.0);  // 2.7 at 3 subdivisions: no tet lies flat on a shell
  }
}

TEST(Primitives, LoadBodyMeshAppliesScaleThenTranslate) {
  MeshSourceDesc desc;
  desc.kind = MeshSourceDesc::Kind::File;
  desc.path = test::test_mesh("cube_v22.msh");
  desc.scale = {0.001, 0.002, -0.003};  // mm -> m, with a mirror on z
  desc.translate = {1, 2, 3};
  LoadReport report;
  VolumeMesh mesh = load_body_mesh(desc, &report);
  MeshQuality q = mesh_quality(mesh);
  EXPECT_NEAR(q.bounds_min[0], 1.0, 1e-15);
  EXPECT_NEAR(q.bounds_max[1], 2.002, 1e-15);
  EXPECT_NEAR(q.bounds_min[2], 2.997, 1e-15);
  EXPECT_NEAR(test::total_volume(mesh), 6e-9, 1e-20);
  EXPECT_GT(q.min_volume, 0.0);  // the mirror was re-oriented

  MeshSourceDesc box;
  box.kind = MeshSourceDesc::Kind::BoxGrid;
  box.size = {1, 1, 1};
  box.cells = {2, 2, 2};
  box.translate = {0, 0, 5};
  EXPECT_NEAR(mesh_quality(load_body_mesh(box)).bounds_min[2], 5.0, 1e-15);

  MeshSourceDesc bad = box;
  bad.scale = {1, 0, 1};
  EXPECT_THROW(load_body_mesh(bad), InputError);
}

}  // namespace
}  // namespace tacta
