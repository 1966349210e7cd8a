// The boundary keys of a body: prescribed displacements (constant, ramp, table; axes), plates and
// probes load into their descriptions, and each malformed value is an error at its key.
#include <gtest/gtest.h>

#include "fake_schemas.hpp"

namespace tacta::testing {
namespace {

std::string with_body_keys(const std::string& keys) { return yaml(kMinimalScene) + keys; }

TEST(SceneBoundary, PrescribedFormsLoad) {
  const SceneDesc s = load(with_body_keys(R"(    prescribed:
      - {region: {nodes: [0, 1]}, displacement: [0, 0.001, 0]}
      - {region: {box: {min: [0, 0, 0], max: [1, 1, 1]}}, axes: [x, z], displacement: {ramp: {to: [0.01, 0, 0], start_s: 0.5, duration_s: 2}}}
      - {region: {nodes: [2]}, displacement: {table: [[0, 0, 0, 0], [1, 0, 0.002, 0], [3, 0, 0.002, 0.001]]}}
)"));
  const std::vector<PrescribedDesc>& p = s.bodies[0].prescribed;
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].region.indices, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(p[0].displacement.times_s, (std::vector<double>{0.0}));
  EXPECT_EQ(p[0].displacement.values[0], (Vec3{0, 0.001, 0}));
  EXPECT_EQ(p[0].axes, (std::array<bool, 3>{true, true, true}));
  EXPECT_EQ(p[1].axes, (std::array<bool, 3>{true, false, true}));
  EXPECT_EQ(p[1].displacement.times_s, (std::vector<double>{0.5, 2.5}));
  EXPECT_EQ(p[1].displacement.values[0], (Vec3{0, 0, 0}));
  EXPECT_EQ(p[1].displacement.values[1], (Vec3{0.01, 0, 0}));
  EXPECT_EQ(p[2].displacement.times_s, (std::vector<double>{0, 1, 3}));
  EXPECT_EQ(p[2].displacement.values[2], (Vec3{0, 0.002, 0.001}));
}

TEST(SceneBoundary, PlatesAndProbesLoad) {
  const SceneDesc s = load(with_body_keys(R"(    plates:
      - {name: top, region: {box: {min: [-1, 0.09, -1], max: [1, 1, 1]}}, point: [0, 0.1, 0], normal: [0, -2, 0],
         motion: {ramp: {to: [0, -0.01, 0], duration_s: 1}}, contact: stuck}
      - {name: floor, region: {nodes: [0]}, point: [0, 0, 0], normal: [0, 1, 0]}
    probes:
      - {name: centre, position: [0.05, 0.05, 0.05]}
)"));
  const BodyDesc& b = s.bodies[0];
  ASSERT_EQ(b.plates.size(), 2u);
  EXPECT_EQ(b.plates[0].normal, (Vec3{0, -1, 0}));  // normalised
  EXPECT_TRUE(b.plates[0].stuck);
  EXPECT_FALSE(b.plates[1].stuck);                           // frictionless unless told
  EXPECT_EQ(b.plates[1].motion.values[0], (Vec3{0, 0, 0}));  // a plate that stays put
  ASSERT_EQ(b.probes.size(), 1u);
  EXPECT_EQ(b.probes[0].name, "centre");
  EXPECT_EQ(b.probes[0].rest, (Vec3{0.05, 0.05, 0.05}));
}

void expect_error(const std::string& keys, const std::string& key_path,
                  const std::string& fragment) {
  const InputError e = load_error(with_body_keys(keys));
  EXPECT_EQ(e.where().key_path, key_path) << e.what();
  EXPECT_GT(e.where().line, 5) << e.what();
  EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
}

TEST(SceneBoundary, MalformedValuesAreErrorsAtTheirKey) {
  expect_error(
      "    prescribed: [{region: {nodes: [0]}, displacement: {table: [[0, 0, 0, 0], [0, 1, 1, "
      "1]]}}]\n",
      "bodies[0].prescribed[0].displacement.table[1]", "strictly increasing");
  expect_error("    prescribed: [{region: {nodes: [0]}, displacement: {table: [[0, 0, 0]]}}]\n",
               "bodies[0].prescribed[0].displacement.table[0]", "4");
  expect_error("    prescribed: [{region: {nodes: [0]}, displacement: {ramp: {to: [0, 0, 1]}}}]\n",
               "bodies[0].prescribed[0].displacement.ramp.duration_s", "missing");
  expect_error(
      "    prescribed: [{region: {nodes: [0]}, displacement: {ramp: {to: [0, 0, 1], duration_s: "
      "0}}}]\n",
      "bodies[0].prescribed[0].displacement.ramp.duration_s", "> 0");
  expect_error("    prescribed: [{region: {nodes: [0]}, displacement: [0, 0, 0], axes: [x, w]}]\n",
               "bodies[0].prescribed[0].axes[1]", "'w'");
  expect_error("    prescribed: [{region: {nodes: [0]}, displacement: [0, 0, 0], axes: [x, x]}]\n",
               "bodies[0].prescribed[0].axes[1]", "twice");
  expect_error("    prescribed: [{region: {nodes: [99]}, displacement: [0, 0, 0]}]\n",
               "bodies[0].prescribed[0].region.nodes[0]", "26");
  expect_error("    prescribed: [{region: {nodes: [0]}, displacment: [0, 0, 0]}]\n",
               "bodies[0].prescribed[0].displacment", "did you mean 'displacement'");
  expect_error(
      "    plates: [{name: p, region: {nodes: [0]}, point: [0, 0, 0], normal: [0, 0, 0]}]\n",
      "bodies[0].plates[0].normal", "non-zero normal");
  expect_error(
      "    plates: [{name: p, region: {nodes: [0]}, point: [0, 0, 0], normal: [0, 1, 0], contact: "
      "glued}]\n",
      "bodies[0].plates[0].contact", "'glued'");
  expect_error(R"(    plates:
      - {name: p, region: {nodes: [0]}, point: [0, 0, 0], normal: [0, 1, 0]}
      - {name: p, region: {nodes: [1]}, point: [0, 0, 0], normal: [0, 1, 0]}
)",
               "bodies[0].plates[1].name", "used twice");
  expect_error("    probes: [{name: a, position: [0, 0]}]\n", "bodies[0].probes[0].position", "3");
}

}  // namespace
}  // namespace tacta::testing
