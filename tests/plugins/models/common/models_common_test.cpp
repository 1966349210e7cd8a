// Support library for model plugins: geometry, Lamé conversions, meshes, divergence guard.
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "tacta/models/divergence_guard.hpp"
#include "tacta/models/edge_graph.hpp"
#include "tacta/models/lame.hpp"
#include "tacta/models/state_blob.hpp"
#include "tacta/models/test_meshes.hpp"
#include "tacta/models/tet_geometry.hpp"

using namespace tacta::models;

TEST(ModelsCommon, LameRoundTrip) {
  const Lame l = lame_from_young(1e5, 0.3);
  EXPECT_NEAR(l.mu, 1e5 / 2.6, 1e-9);
  EXPECT_NEAR(young_from_lame(l.lambda, l.mu), 1e5, 1e-6);
  EXPECT_NEAR(poisson_from_lame(l.lambda, l.mu), 0.3, 1e-12);
  EXPECT_NEAR(p_wave_speed(1.0, 0.01, 1.0), std::sqrt(1.02), 1e-15);
}

TEST(ModelsCommon, ShapeGradientsReproduceLinearField) {
  const Vec3 x0(0, 0, 0), x1(1, 0.1, 0), x2(0.2, 1, 0), x3(0.1, 0.3, 1.2);
  const auto g = tet_shape_gradients(x0, x1, x2, x3);
  const Vec3 a(0.3, -0.7, 1.1);  // field f(x) = a . x has gradient a
  const Vec3 grad = g[0] * a.dot(x0) + g[1] * a.dot(x1) + g[2] * a.dot(x2) + g[3] * a.dot(x3);
  EXPECT_LT((grad - a).norm(), 1e-12);
  EXPECT_GT(tet_signed_volume(x0, x1, x2, x3), 0.0);
}

TEST(ModelsCommon, BoxMeshVolumeOrientationAndBoundary) {
  const TestMesh m = box_tet_mesh({2, 3, 4}, {0.2, 0.3, 0.8}, 1000.0);
  ASSERT_EQ(m.tets.size(), 4u * 6 * 24);
  double volume = 0;
  for (size_t t = 0; t < m.tets.size(); t += 4) {
    const double v = tet_signed_volume(node_position(m.positions.data(), m.tets[t]),
                                       node_position(m.positions.data(), m.tets[t + 1]),
                                       node_position(m.positions.data(), m.tets[t + 2]),
                                       node_position(m.positions.data(), m.tets[t + 3]));
    EXPECT_GT(v, 0.0);
    volume += v;
  }
  EXPECT_NEAR(volume, 0.2 * 0.3 * 0.8, 1e-12);
  double mass = 0;
  for (double x : m.masses) mass += x;
  EXPECT_NEAR(mass, 1000.0 * 0.048, 1e-9);
  // Closed outward surface: sum of area vectors is zero, divergence theorem gives the volume.
  double enclosed = 0;
  for (size_t f = 0; f < m.triangles.size(); f += 3) {
    const Vec3 a = node_position(m.positions.data(), m.triangles[f]);
    const Vec3 b = node_position(m.positions.data(), m.triangles[f + 1]);
    const Vec3 c = node_position(m.positions.data(), m.triangles[f + 2]);
    enclosed += a.dot(b.cross(c)) / 6.0;
  }
  EXPECT_NEAR(enclosed, 0.048, 1e-12);
  // 2 boundary triangles per boundary square.
  EXPECT_EQ(m.triangles.size() / 3, 2u * 2 * (2 * 3 + 3 * 4 + 2 * 4));
}

TEST(ModelsCommon, EdgeGraphOfGridAndUnitSquare) {
  const TestMesh square = quad_grid_mesh(1, 1, 1.0, 1.0, 1.0);
  ASSERT_EQ(square.node_count(), 4u);
  EXPECT_EQ(square.edges.size(), 8u);  // the four sides, no diagonals
  EXPECT_DOUBLE_EQ(square.masses[3], 0.25);
  const EdgeGraph g = EdgeGraph::from_mesh(square.view());
  EXPECT_EQ(g.degree(3), 2u);  // NE touches NW and SE only
  EXPECT_EQ(g.find_edge(0, 3), UINT32_MAX);
  EXPECT_NE(g.find_edge(3, 1), UINT32_MAX);
  const TestMesh grid = grid_edge_mesh({2, 2, 2}, {1, 1, 1}, 1.0);
  EXPECT_EQ(EdgeGraph::from_mesh(grid.view()).degree(13), 6u);  // the centre node
}

TEST(ModelsCommon, DivergenceGuardFlagsNaNAndStretch) {
  const TestMesh m = box_tet_mesh({1, 1, 1}, {1, 1, 1}, 1.0);
  const DivergenceGuard guard(m.view(), 10.0);
  std::vector<double> x = m.positions, v(x.size(), 0.0);
  EXPECT_EQ(guard.check(x.data(), v.data()), TACTA_STEP_OK);
  for (size_t i = 0; i < x.size(); i += 3) x[i] += 1e6;  // rigid translation is no fault
  EXPECT_EQ(guard.check(x.data(), v.data()), TACTA_STEP_OK);
  x = m.positions;
  x[3 * 7] = 20.0;  // one corner 20 m away on a 1 m cube
  EXPECT_EQ(guard.check(x.data(), v.data()), TACTA_STEP_DIVERGED);
  x = m.positions;
  v[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(guard.check(x.data(), v.data()), TACTA_STEP_NOT_FINITE);
}

// The checkpoint blob: what one field list writes it reads back; a blob of another model, layout
// or mesh, a cut one, one with bytes past its end or with a vector of another length is refused
// with a reason and leaves the fields as they were.
struct BlobFields {
  std::vector<double> history = {1.5, -2.25, 3.0};
  uint64_t count = 7;
  void fields(StateIo& io) {
    io.vector(history, "history");
    io.value(count, "count");
  }
};

std::string load_error(const StateHeader& header, const std::vector<unsigned char>& blob,
                       BlobFields& into) {
  try {
    load_state_blob(header, blob.data(), blob.size(), [&](StateIo& io) { into.fields(io); });
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return {};
}

TEST(StateBlob, RoundTripsAndRefusesForeignOrDamagedBlobs) {
  const StateHeader header{"toy_model", 2, 10, 4};
  BlobFields saved;
  std::vector<unsigned char> blob(
      save_state_blob(header, nullptr, 0, [&](StateIo& io) { saved.fields(io); }));
  ASSERT_EQ(
      save_state_blob(header, blob.data(), blob.size(), [&](StateIo& io) { saved.fields(io); }),
      blob.size());
  BlobFields loaded;
  loaded.history = {0, 0, 0};
  loaded.count = 0;
  EXPECT_EQ(load_error(header, blob, loaded), "");
  EXPECT_EQ(loaded.history, saved.history);
  EXPECT_EQ(loaded.count, 7u);

  BlobFields untouched;
  untouched.count = 99;
  const auto refused = [&](const StateHeader& h, const std::vector<unsigned char>& b,
                           const std::string& reason) {
    const std::string why = load_error(h, b, untouched);
    EXPECT_NE(why.find(reason), std::string::npos) << why;
    EXPECT_EQ(untouched.count, 99u) << "a refused blob changed the instance";
  };
  refused({"other_model", 2, 10, 4}, blob, "model 'toy_model'");
  refused({"toy_model", 3, 10, 4}, blob, "layout version 2");
  refused({"toy_model", 2, 11, 4}, blob, "10 nodes and 4 elements");
  refused(header, {blob.begin(), blob.end() - 1}, "the blob ends");
  std::vector<unsigned char> longer = blob;
  longer.push_back(0);
  refused(header, longer, "1 bytes past its last field");
  refused(header, std::vector<unsigned char>(blob.size(), 0xAB), "not a model state blob");
  untouched.history.resize(4);
  refused(header, blob, "'history' holds 3 values in the blob, this instance 4");
}
