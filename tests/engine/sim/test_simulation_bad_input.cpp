// Bad input at load time: an unknown model name, a fixed box that holds no node, a node index
// out of range in initial.displacement. Each is an InputError naming the scene file and the key,
// and nothing stays half-built: every model instance made before the error is destroyed (the test
// model counts its live instances).
#include <dlfcn.h>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

// Live instances of test_fault_model, read from the plugin the registry loaded.
int live_fault_models() {
  plugins();  // make sure the registry (and so the plugin) is loaded
  const std::string path = std::string(TACTA_SIM_TEST_PLUGIN_DIR) + "/tacta_test_fault_model.so";
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD);
  if (handle == nullptr) {
    ADD_FAILURE() << "the test model is not loaded: " << path;
    return -1;
  }
  auto count = reinterpret_cast<int (*)()>(dlsym(handle, "tacta_test_fault_model_live_instances"));
  const int live = count != nullptr ? count() : -1;
  dlclose(handle);  // drops only the reference taken here
  return live;
}

// A good first body (the counting test model) and a second body the test breaks.
std::string two_bodies(
    const std::string& second_body_extra,
    const std::string& second_mesh = "{box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2]}}") {
  return R"(
name: broken
gravity: [0, 0, 0]
bodies:
  - name: good
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2]}}
    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
    model: test_fault_model
  - name: bad
    mesh: )" +
         second_mesh + R"(
    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
    model: test_fault_model
)" + second_body_extra;
}

TEST(SimulationBadInput, UnknownModelNameNamesTheFileAndKey) {
  const std::string text = R"(
name: unknown_model
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2]}}
    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
    model: tensor_mas
)";
  try {
    scene_from_text(text, "unknown_model");
    FAIL() << "an unknown model loaded";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.where().file, scene_path("unknown_model"));
    EXPECT_EQ(e.where().line, 7);
    EXPECT_NE(what.find(scene_path("unknown_model") + ":7:"), std::string::npos) << what;
    EXPECT_NE(what.find("bodies[0].model"), std::string::npos) << what;
    EXPECT_NE(what.find("tensor_mas"), std::string::npos) << what;
    EXPECT_NE(what.find("did you mean 'tensor_mass'"), std::string::npos) << what;
  }
}

TEST(SimulationBadInput, FixedBoxHoldingNoNodeFailsAndBuildsNothing) {
  const SceneDesc scene = scene_from_text(
      two_bodies("    fixed: [{box: {min: [5, 5, 5], max: [6, 6, 6]}}]\n"), "fixed_box_empty");
  ASSERT_EQ(live_fault_models(), 0);
  try {
    Simulation simulation(scene, plugins());
    FAIL() << "a fixed box with no node was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.where().file, scene_path("fixed_box_empty"));
    EXPECT_NE(what.find(scene_path("fixed_box_empty")), std::string::npos) << what;
    EXPECT_NE(what.find("bodies[1]"), std::string::npos) << what;
    EXPECT_NE(what.find("fixed"), std::string::npos) << what;
  }
  EXPECT_EQ(live_fault_models(), 0) << "the first body's model instance outlived the failed load";
}

TEST(SimulationBadInput, DisplacedNodeOutOfRangeFailsAndBuildsNothing) {
  // A sphere's node count is known only once it is meshed, so the loader cannot reject it.
  const SceneDesc scene = scene_from_text(
      two_bodies("    initial:\n      displacement: [{node: 100000, value: [0.01, 0, 0]}]\n",
                 "{sphere: {radius: 0.05, subdivisions: 1}}"),
      "displacement_out_of_range");
  try {
    Simulation simulation(scene, plugins());
    FAIL() << "a node index out of range was accepted";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.where().file, scene_path("displacement_out_of_range"));
    EXPECT_NE(what.find("bodies[1]"), std::string::npos) << what;
    EXPECT_NE(what.find("initial.displacement"), std::string::npos) << what;
    EXPECT_NE(what.find("100000"), std::string::npos) << what;
  }
  EXPECT_EQ(live_fault_models(), 0);
}

TEST(SimulationBadInput, TheCountingModelReallyCounts) {
  // Guards the two tests above: a built simulation holds one instance per body.
  const SceneDesc scene = scene_from_text(two_bodies(""), "two_good_bodies");
  {
    Simulation simulation(scene, plugins());
    EXPECT_EQ(live_fault_models(), 2);
  }
  EXPECT_EQ(live_fault_models(), 0);
}

// A device needs the broad phase for its proxy's surface queries even when collision response
// is off (docs/SCENES.md: no collision section = collision off). The broad phase must then be
// built with its default parameters.
TEST(SimulationBadInput, DeviceWithCollisionOffStillBuilds) {
  std::string text = kCubePressScene;
  text = text.substr(0, text.find("collision:"));
  for (const std::string& tail : {std::string(), std::string("collision: {enabled: false}\n")}) {
    const SceneDesc scene = scene_from_text(text + tail, "device_collision_off");
    ASSERT_FALSE(scene.collision.enabled);
    try {
      Simulation simulation(scene, plugins());
    } catch (const InputError& e) {
      ADD_FAILURE() << "scene with '" << (tail.empty() ? "no collision section" : tail)
                    << "': " << e.what();
    }
  }
}

}  // namespace
}  // namespace tacta::simtest
