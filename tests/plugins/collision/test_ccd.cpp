// CCD plugin: zero false negatives on every query of tests/data/ccd, degenerate unit cases,
// and the plain baseline exercised through the same ABI.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <sstream>
#include <string>

#include "plugin_fixture.hpp"
#include "tacta/ccd_queries.hpp"
#include "tacta/collision_api.h"
#include "tacta/error.hpp"

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
  const auto queries = tacta::read_ccd_paths({std::string(TACTA_SOURCE_DIR) + "/tests/data/ccd"});
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
  const auto queries = tacta::read_ccd_paths({std::string(TACTA_SOURCE_DIR) + "/tests/data/ccd"});
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

namespace {

// The reader's bounds: each bad row names its line and column; 8 good rows make one query.
std::string reader_error(const std::string& text) {
  std::istringstream in(text);
  try {
    (void)tacta::read_ccd_queries(in, "q.csv", true);
  } catch (const tacta::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(CcdQueryReader, ReadsEightRowsAsOneQuery) {
  std::string text;
  for (int row = 0; row < 8; ++row) text += "3,4,-1,2,5,1," + std::string(row ? "0" : "1") + "\r\n";
  std::istringstream in(text + "\n");
  const auto queries = tacta::read_ccd_queries(in, "q.csv", true);
  ASSERT_EQ(queries.size(), 1u);
  EXPECT_TRUE(queries[0].truth);
  EXPECT_TRUE(queries[0].vertex_face);
  EXPECT_EQ(queries[0].origin, "q.csv:1");
  EXPECT_EQ(queries[0].points[21], 0.75);
  EXPECT_EQ(queries[0].points[22], -0.5);
  EXPECT_EQ(queries[0].points[23], 5.0);
}

TEST(CcdQueryReader, BadRowsNameLineAndColumn) {
  const std::string good = "1,1,1,1,1,1,0\n";
  EXPECT_EQ(reader_error(good + "1,1,1,1,1,1\n"),
            "q.csv:2: expected 7 comma-separated integers x_num,x_den,y_num,y_den,z_num,z_den,"
            "truth");
  EXPECT_EQ(reader_error(good + "1,1,1,1,1,1,0,0\n").substr(0, 8), "q.csv:2:");
  EXPECT_EQ(reader_error("1,1,x,1,1,1,0\n"),
            "q.csv:1:3: expected an integer of at most 64 digits, found 'x'");
  EXPECT_EQ(reader_error("1,3,1,1,1,1,0\n"),
            "q.csv:1:2: expected a power-of-two denominator, found '3'");
  EXPECT_EQ(reader_error("1,0,1,1,1,1,0\n").substr(0, 10), "q.csv:1:2:");
  EXPECT_EQ(reader_error("1,1,1,1,1,1,2\n"),
            "q.csv:1:7: expected the truth column 0 or 1, found '2'");
  EXPECT_EQ(reader_error(std::string(2000, '1') + "\n"),
            "q.csv:1: line longer than 1024 characters");
  EXPECT_EQ(reader_error(good + good),
            "q.csv:2: the row count is not a multiple of 8 (one query is 8 rows)");
}

}  // namespace
