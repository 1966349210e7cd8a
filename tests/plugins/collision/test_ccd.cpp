// CCD plugin: zero false negatives on every query of tests/data/ccd, degenerate unit cases,
// and the plain baseline exercised through the same ABI.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

#include "ccd_queries.hpp"
#include "plugin_fixture.hpp"
#include "tacta/collision_api.h"

namespace {

using tacta::testing::LoadedPlugin;

class CcdPlugin : public ::testing::Test {
 protected:
  void SetUp() override { instance_ = make(0); }
  void TearDown() override {
    if (instance_ != nullptr) api().destroy(instance_);
  }
  const tacta_collision_api& api() { return plugin_.api<tacta_collision_api>("ccd"); }
  void* make(int method) {
    auto params = tacta::testing::default_params(plugin_.descriptor("ccd"));
    params[0].number = method;
    tacta_collision_setup setup{sizeof setup, params.data(), static_cast<uint32_t>(params.size()),
                                0.001};
    void* instance = nullptr;
    char message[256] = {0};
    EXPECT_EQ(api().create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
    return instance;
  }
  bool vf(std::initializer_list<double> p, tacta_ccd_hit& hit) {
    std::vector<double> v(p);
    return api().vertex_face(instance_, v.data(), &hit) != 0;
  }
  bool ee(std::initializer_list<double> p, tacta_ccd_hit& hit) {
    std::vector<double> v(p);
    return api().edge_edge(instance_, v.data(), &hit) != 0;
  }
  LoadedPlugin plugin_{"tacta_ccd.so"};
  void* instance_ = nullptr;
};

TEST_F(CcdPlugin, DescriptorIsCollisionKindWithRequiredEntries) {
  const tacta_descriptor& d = plugin_.descriptor("ccd");
  EXPECT_EQ(d.kind, TACTA_KIND_COLLISION);
  EXPECT_EQ(d.api_size, sizeof(tacta_collision_api));
  for (const tacta_api_field& field : tacta_collision_api_fields) {
    const void* entry =
        *reinterpret_cast<const void* const*>(static_cast<const char*>(d.api) + field.offset);
    if (field.required) {
      EXPECT_NE(entry, nullptr) << field.name;
    }
  }
  EXPECT_NE(api().vertex_face, nullptr);
  EXPECT_NE(api().edge_edge, nullptr);
  EXPECT_NE(api().detect, nullptr);
}

TEST_F(CcdPlugin, NoFalseNegativeOnAnyReferenceQuery) {
  const auto queries =
      tacta::testing::read_ccd_folder(std::string(TACTA_SOURCE_DIR) + "/tests/data/ccd");
  ASSERT_EQ(queries.size(), 2824u);
  int positives = 0, false_positives = 0;
  for (const auto& q : queries) {
    tacta_ccd_hit hit{};
    const bool found = q.vertex_face ? api().vertex_face(instance_, q.points, &hit) != 0
                                     : api().edge_edge(instance_, q.points, &hit) != 0;
    if (q.truth) {
      ++positives;
      ASSERT_TRUE(found) << "missed contact at " << q.origin;
      EXPECT_GE(hit.toi, 0.0);
      EXPECT_LE(hit.toi, 1.0);
    } else if (found) {
      ++false_positives;
    }
  }
  EXPECT_EQ(positives, 287);  // the ground truth count of the data set
  std::printf("inclusion: 0 false negatives, %d false positives\n", false_positives);
  // False positives cost time only; keep them a small share so the test notices a regression.
  EXPECT_LT(false_positives, static_cast<int>(queries.size()) / 10);
}

TEST_F(CcdPlugin, VertexThroughStillTriangleGivesTimeAndBarycentric) {
  // Triangle in z = 0; vertex falls from z = 1 to z = -1 above (0.25, 0.25): contact at t = 0.5.
  tacta_ccd_hit hit{};
  ASSERT_TRUE(vf({0.25, 0.25, 1,  0, 0, 0, 1, 0, 0, 0, 1, 0,  //
                  0.25, 0.25, -1, 0, 0, 0, 1, 0, 0, 0, 1, 0},
                 hit));
  EXPECT_NEAR(hit.toi, 0.5, 1e-5);
  EXPECT_LE(hit.toi, 0.5);  // a lower bound
  EXPECT_NEAR(hit.barycentric[1], 0.25, 1e-3);
  EXPECT_NEAR(hit.barycentric[2], 0.25, 1e-3);
}

TEST_F(CcdPlugin, DegenerateVertexFaceCases) {
  tacta_ccd_hit hit{};
  // Zero motion, vertex in the triangle's plane and inside: touching over the whole tick.
  EXPECT_TRUE(vf({0.2, 0.2, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
                  0.2, 0.2, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0},
                 hit));
  EXPECT_EQ(hit.toi, 0.0);
  // Zero motion, apart.
  EXPECT_FALSE(vf({0.2, 0.2, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
                   0.2, 0.2, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0},
                  hit));
  // Touching exactly at t = 1 at a triangle corner.
  EXPECT_TRUE(vf({1, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
                  1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0},
                 hit));
  // Coplanar sliding into the triangle through an edge.
  EXPECT_TRUE(vf({-1,  0.2, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
                  0.2, 0.2, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0},
                 hit));
  // Degenerate (zero-area) triangle crossed by the vertex: a segment-point contact.
  EXPECT_TRUE(vf({0.5, 1,  0, 0, 0, 0, 1, 0, 0, 1, 0, 0,  //
                  0.5, -1, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0},
                 hit));
  // Passing just outside a corner misses.
  EXPECT_FALSE(vf({1.001, 0.001, 1,  0, 0, 0, 1, 0, 0, 0, 1, 0,  //
                   1.001, 0.001, -1, 0, 0, 0, 1, 0, 0, 0, 1, 0},
                  hit));
}

TEST_F(CcdPlugin, DegenerateEdgeEdgeCases) {
  tacta_ccd_hit hit{};
  // Crossing edges: a along x at z = 1 moving to z = -1, b along y at z = 0.
  EXPECT_TRUE(ee({-1, 0, 1,  1, 0, 1,  0, -1, 0, 0, 1, 0,  //
                  -1, 0, -1, 1, 0, -1, 0, -1, 0, 0, 1, 0},
                 hit));
  EXPECT_NEAR(hit.toi, 0.5, 1e-4);
  EXPECT_NEAR(hit.barycentric[0], 0.5, 1e-3);
  // Parallel collinear overlapping edges, no motion.
  EXPECT_TRUE(ee({0, 0, 0, 2, 0, 0, 1, 0, 0, 3, 0, 0,  //
                  0, 0, 0, 2, 0, 0, 1, 0, 0, 3, 0, 0},
                 hit));
  // Parallel edges a unit apart moving together: never touch.
  EXPECT_FALSE(ee({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0,  //
                   0, 0, 5, 1, 0, 5, 0, 1, 5, 1, 1, 5},
                  hit));
  // Zero-length edge (a point) crossing a segment.
  EXPECT_TRUE(ee({0.5, 1,  0, 0.5, 1,  0, 0, 0, 0, 1, 0, 0,  //
                  0.5, -1, 0, 0.5, -1, 0, 0, 0, 0, 1, 0, 0},
                 hit));
}

TEST_F(CcdPlugin, NotFiniteInputIsReportedNotCrashed) {
  tacta_ccd_hit hit{};
  const double nan = std::nan("");
  EXPECT_FALSE(vf({nan, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0}, hit));
}

TEST_F(CcdPlugin, PlainBaselineRunsThroughTheSameAbi) {
  void* plain = make(1);
  ASSERT_NE(plain, nullptr);
  const double p[24] = {0.25, 0.25, 1,  0, 0, 0, 1, 0, 0, 0, 1, 0,
                        0.25, 0.25, -1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  tacta_ccd_hit hit{};
  EXPECT_EQ(api().vertex_face(plain, p, &hit), 1);
  EXPECT_NEAR(hit.toi, 0.5, 1e-12);
  api().destroy(plain);
}

}  // namespace

namespace {

// The plain baseline is expected to miss some contacts; this records how many (for the docs)
// and checks our conservative test does strictly better on the same queries.
TEST_F(CcdPlugin, PlainBaselineMissesWhereOursDoesNot) {
  void* plain = make(1);
  const auto queries =
      tacta::testing::read_ccd_folder(std::string(TACTA_SOURCE_DIR) + "/tests/data/ccd");
  int plain_misses = 0, plain_false_positives = 0;
  for (const auto& q : queries) {
    tacta_ccd_hit hit{};
    const bool found = q.vertex_face ? api().vertex_face(plain, q.points, &hit) != 0
                                     : api().edge_edge(plain, q.points, &hit) != 0;
    plain_misses += q.truth && !found;
    plain_false_positives += !q.truth && found;
  }
  std::printf("plain Moore-Wilhelms: %d false negatives, %d false positives of %zu queries\n",
              plain_misses, plain_false_positives, queries.size());
  EXPECT_GT(plain_misses, 0);
  api().destroy(plain);
}

}  // namespace
