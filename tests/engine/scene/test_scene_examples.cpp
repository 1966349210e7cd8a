// The example scenes in scenes/examples load (with stand-in plugin schemas).
#include <gtest/gtest.h>

#include <filesystem>

#include "fake_schemas.hpp"

namespace tacta::testing {
namespace {

const std::filesystem::path kExamples = std::filesystem::path(TACTA_SOURCE_DIR) / "scenes/examples";

TEST(SceneExamples, EveryExampleLoads) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kExamples)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW({
      try {
        load_scene(entry.path().string(), fake_schemas());
      } catch (const InputError& e) {
        ADD_FAILURE() << e.what();
        throw;
      }
    });
    ++count;
  }
  EXPECT_GE(count, 3);
}

TEST(SceneExamples, BeamProbeIsTheFarCorner) {
  const SceneDesc s = load_scene((kExamples / "beam_under_gravity.yaml").string(), fake_schemas());
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].model, "corotational_fem");
  EXPECT_EQ(s.bodies[0].mesh.kind, MeshSourceDesc::Kind::BeamGrid);
  EXPECT_EQ(s.bodies[0].probe_node, 35u);
}

TEST(SceneExamples, StylusTouchesTheCube) {
  const SceneDesc s = load_scene((kExamples / "stylus_poke.yaml").string(), fake_schemas(),
                                 {"devices.stylus.params.depth=0.03"});
  ASSERT_EQ(s.devices.size(), 1u);
  EXPECT_EQ(s.devices[0].plugin, "sim_stylus");
  EXPECT_EQ(s.devices[0].touches, "cube");
  EXPECT_DOUBLE_EQ(s.devices[0].params.find("depth")->number, 0.03);
  EXPECT_TRUE(s.collision.enabled);
}

}  // namespace
}  // namespace tacta::testing
