// Every scene the project ships (scenes/**.yaml) loads against the real plugins of the build
// tree, builds its world (the models accept the meshes) and runs 50 ms without a fault, except
// where a scene is a documented divergence case.
#include <algorithm>
#include <filesystem>
#include <gtest/gtest.h>

#include "tacta/plugin_registry.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"

namespace tacta::testing {
namespace {

const std::filesystem::path kScenes = std::filesystem::path(TACTA_SOURCE_DIR) / "scenes";

class ShippedScenes : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    plugins_ = new PluginRegistry(PluginRegistry::DefaultPaths::Skip);
    plugins_->add_path(TACTA_PLUGIN_DIR);
    plugins_->load();
  }
  static void TearDownTestSuite() {
    delete plugins_;
    plugins_ = nullptr;
  }
  static PluginRegistry* plugins_;
};
PluginRegistry* ShippedScenes::plugins_ = nullptr;

TEST_F(ShippedScenes, EverySceneLoadsBuildsAndRuns) {
  RegistrySchemas schemas(*plugins_);
  int count = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(kScenes)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    ++count;
    try {
      const SceneDesc scene = load_scene(entry.path().string(), schemas);
      // A network device waits for its peer at connect: those scenes run end to end in their
      // devices' own tests (tests/plugins/devices: net_teleoperation, openigtlink).
      const bool waits_for_peer = std::any_of(
          scene.devices.begin(), scene.devices.end(),
          [](const DeviceDesc& d) { return d.plugin == "net" || d.plugin == "openigtlink"; });
      if (waits_for_peer) continue;
      Simulation simulation(scene, *plugins_);
      RunOptions options;
      options.duration_s = 0.05;
      const RunResult result = simulation.run(options);
      EXPECT_EQ(result.exit_code, 0) << "a body faulted in the first 50 ms";
      EXPECT_GE(result.schedule.ticks, 1u);
    } catch (const InputError& e) {
      ADD_FAILURE() << e.what();
    }
  }
  EXPECT_GE(count, 6);
}

TEST_F(ShippedScenes, BeamProbeIsTheFarCorner) {
  RegistrySchemas schemas(*plugins_);
  const SceneDesc s = load_scene((kScenes / "examples/beam_under_gravity.yaml").string(), schemas);
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].model, "corotational_fem");
  EXPECT_EQ(s.bodies[0].mesh.kind, MeshSourceDesc::Kind::BeamGrid);
  EXPECT_EQ(s.bodies[0].probe_node, 35u);
}

TEST_F(ShippedScenes, StylusTouchesTheCube) {
  RegistrySchemas schemas(*plugins_);
  const SceneDesc s = load_scene((kScenes / "examples/stylus_poke.yaml").string(), schemas,
                                 {"devices.stylus.params.depth=0.03"});
  ASSERT_EQ(s.devices.size(), 1u);
  EXPECT_EQ(s.devices[0].plugin, "sim_stylus");
  EXPECT_EQ(s.devices[0].touches, "cube");
  EXPECT_DOUBLE_EQ(s.devices[0].params.find("depth")->number, 0.03);
  EXPECT_TRUE(s.collision.enabled);
}

}  // namespace
}  // namespace tacta::testing
