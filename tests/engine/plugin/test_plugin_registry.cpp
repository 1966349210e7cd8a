// The plugin loader against real shared libraries: good ones register and work, each broken one
// is refused with a message naming its file and the cause, and refusals do not stop the others.
#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>

#include "tacta/device_api.h"
#include "tacta/error.hpp"
#include "tacta/model_api.h"
#include "tacta/plugin_registry.hpp"

namespace {

using tacta::PluginRegistry;
namespace fs = std::filesystem;

const std::string kGood = TACTA_TEST_GOOD_PLUGIN_DIR;
const std::string kBroken = TACTA_TEST_BROKEN_PLUGIN_DIR;

std::string reason_for(const PluginRegistry& registry, const std::string& file_name) {
  for (const auto& r : registry.refused())
    if (fs::path(r.file).filename() == file_name) return r.reason;
  return "<not refused>";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(PluginRegistry, LoadsGoodPluginsAndFindsThem) {
  PluginRegistry registry(PluginRegistry::DefaultPaths::Skip);
  registry.add_path(kGood);
  registry.load();
  EXPECT_TRUE(registry.refused().empty());
  ASSERT_EQ(registry.list().size(), 2u);  // the model registers its descriptor twice: kept once
  const auto* model = registry.find(TACTA_KIND_MODEL, "test_anchor_springs");
  ASSERT_NE(model, nullptr);
  EXPECT_EQ(model->descriptor->version, 10203u);
  EXPECT_EQ(fs::path(model->file).filename(), "tacta_test_good_model.so");
  EXPECT_EQ(registry.find(TACTA_KIND_DEVICE, "test_anchor_springs"), nullptr);  // kind matters
  ASSERT_NE(registry.find(TACTA_KIND_DEVICE, "test_sine_stylus"), nullptr);
  const auto schema = registry.schema(TACTA_KIND_MODEL, "test_anchor_springs");
  ASSERT_TRUE(schema.has_value());
  ASSERT_EQ(schema->size(), 4u);
  EXPECT_STREQ((*schema)[0].name, "stiffness");
  EXPECT_STREQ((*schema)[0].unit, "N/m");
  EXPECT_FALSE(registry.schema(TACTA_KIND_MODEL, "nope").has_value());
}

TEST(PluginRegistry, SameFileThroughTwoPathsIsHarmless) {
  const fs::path link = fs::path(TACTA_BINARY_DIR) / "tests_plugin_registry_link";
  fs::remove(link);
  fs::create_directory_symlink(kGood, link);
  PluginRegistry registry(PluginRegistry::DefaultPaths::Skip);
  registry.add_path(kGood);
  registry.add_path(link.string());
  registry.load();
  registry.load_directory(kGood);  // and once more by hand
  EXPECT_TRUE(registry.refused().empty());
  EXPECT_EQ(registry.list().size(), 2u);
  fs::remove(link);
}

TEST(PluginRegistry, EachBrokenPluginIsRefusedWithFileAndCause) {
  PluginRegistry registry(PluginRegistry::DefaultPaths::Skip);
  registry.add_path(kGood);
  registry.add_path(kBroken);
  registry.load();
  // Good ones still load; of the duplicate pair the first file (by name) wins.
  EXPECT_NE(registry.find(TACTA_KIND_MODEL, "test_anchor_springs"), nullptr);
  ASSERT_NE(registry.find(TACTA_KIND_MODEL, "test_duplicate"), nullptr);
  EXPECT_EQ(fs::path(registry.find(TACTA_KIND_MODEL, "test_duplicate")->file).filename(),
            "tacta_test_duplicate_a.so");
  EXPECT_EQ(registry.refused().size(), 5u);
  for (const auto& r : registry.refused()) EXPECT_TRUE(contains(r.file, kBroken)) << r.file;

  const std::string no_entry = reason_for(registry, "tacta_test_no_entry.so");
  EXPECT_TRUE(contains(no_entry, "tacta_plugin_entry")) << no_entry;

  const std::string abi = reason_for(registry, "tacta_test_abi_float.so");
  EXPECT_TRUE(contains(abi, "ABI refused")) << abi;
  EXPECT_TRUE(contains(abi, "build bit 0")) << abi;
  EXPECT_TRUE(contains(abi, "scalar type (double vs float)")) << abi;

  const std::string missing = reason_for(registry, "tacta_test_missing_step.so");
  EXPECT_TRUE(contains(missing, "required function 'step'")) << missing;
  EXPECT_TRUE(contains(missing, "test_missing_step")) << missing;

  const std::string duplicate = reason_for(registry, "tacta_test_duplicate_b.so");
  EXPECT_TRUE(contains(duplicate, "test_duplicate")) << duplicate;
  EXPECT_TRUE(contains(duplicate, kBroken + "/tacta_test_duplicate_a.so")) << duplicate;

  const std::string dlopen = reason_for(registry, "tacta_test_absent_dependency.so");
  EXPECT_TRUE(contains(dlopen, "dlopen failed")) << dlopen;
  EXPECT_TRUE(contains(dlopen, "libtacta_test_absent_dep.so")) << dlopen;

  // Nothing from a refused file stays registered.
  EXPECT_EQ(registry.find(TACTA_KIND_MODEL, "test_missing_step"), nullptr);
  EXPECT_EQ(registry.find(TACTA_KIND_MODEL, "test_float_model"), nullptr);
}

TEST(PluginRegistry, UnknownNameSuggestsTheClosest) {
  PluginRegistry registry(PluginRegistry::DefaultPaths::Skip);
  registry.add_path(kGood);
  registry.load();
  const std::string message = registry.unknown_name_message(TACTA_KIND_MODEL, "test_anchor_spring");
  EXPECT_TRUE(contains(message, "no model plugin named 'test_anchor_spring'")) << message;
  EXPECT_TRUE(contains(message, "did you mean 'test_anchor_springs'?")) << message;
  try {
    registry.require(TACTA_KIND_DEVICE, "something_else");
    FAIL() << "require must throw for an unknown name";
  } catch (const tacta::InputError& error) {
    EXPECT_TRUE(contains(error.what(), "available device plugins: test_sine_stylus"))
        << error.what();
    EXPECT_FALSE(contains(error.what(), "did you mean")) << error.what();
  }
  const std::string none = registry.unknown_name_message(TACTA_KIND_COLLISION, "bvh");
  EXPECT_TRUE(contains(none, "no collision plugins are loaded")) << none;
}

TEST(PluginRegistry, ClosestNamesRanksByEditDistance) {
  const std::vector<std::string> names{"tensor_mass", "mass_spring", "fd_debunne",
                                       "corotational_fem"};
  EXPECT_EQ(tacta::closest_names("tensor_mas", names), std::vector<std::string>{"tensor_mass"});
  EXPECT_EQ(tacta::closest_names("mass_sprign", names), std::vector<std::string>{"mass_spring"});
  EXPECT_TRUE(tacta::closest_names("bullet", names).empty());
  EXPECT_TRUE(tacta::closest_names("tensor_mass", names).empty());  // exact is not a suggestion
}

TEST(PluginRegistry, BadPathIsAnInputError) {
  PluginRegistry registry(PluginRegistry::DefaultPaths::Skip);
  EXPECT_THROW(registry.add_path("/nonexistent/tacta/plugins"), tacta::InputError);
}

TEST(PluginRegistry, EnvironmentPathIsSearched) {
  ::setenv("TACTA_PLUGIN_PATH", ("/nonexistent::" + kGood).c_str(), 1);
  PluginRegistry registry;  // default search paths
  const auto paths = registry.search_paths();
  bool found = false;
  for (const auto& p : paths) found = found || p == kGood;
  EXPECT_TRUE(found);
  EXPECT_EQ(paths.front(), TACTA_PLUGIN_DIR);  // the build tree comes first
  registry.load();
  ::unsetenv("TACTA_PLUGIN_PATH");
  EXPECT_NE(registry.find(TACTA_KIND_DEVICE, "test_sine_stylus"), nullptr);
}

// The loaded model works through its C table: one step matches the closed form.
TEST(PluginRegistry, LoadedModelStepsAsSpecified) {
  PluginRegistry registry(PluginRegistry::DefaultPaths::Skip);
  registry.add_path(kGood);
  registry.load();
  const auto& entry = registry.require(TACTA_KIND_MODEL, "test_anchor_springs");
  const auto& api = *static_cast<const tacta_model_api*>(entry.descriptor->api);
  const double rest[3] = {0, 0, 0};
  tacta_mesh_view mesh{};
  mesh.node_count = 1;
  mesh.rest_positions = rest;
  mesh.dimension = 3;
  const tacta_material material{};
  const double masses[1] = {2.0};  // kg
  const uint8_t fixed[1] = {0};
  const double offset[3] = {0, 0, 0};
  tacta_param_value params[4] = {{100.0, nullptr, nullptr, 0},
                                 {0.0, "semi_implicit", nullptr, 0},
                                 {0.0, nullptr, offset, 3},
                                 {1.0, nullptr, nullptr, 0}};
  const tacta_model_setup setup{
      sizeof(tacta_model_setup), &mesh, &material, masses, fixed, params, 4, 1e-3, nullptr};
  void* instance = nullptr;
  char message[256] = {0};
  ASSERT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
  double x[3] = {0.01, 0, 0}, v[3] = {0, 0, 0};
  const double f[3] = {0, 0, 0};
  tacta_body_state state{1, x, v, f, 0.0};
  EXPECT_EQ(api.step(instance, &state, 1e-3), TACTA_STEP_OK);
  const double v1 = -1e-3 * 100.0 * 0.01 / 2.0;  // dt (-k u) / m, m/s
  EXPECT_DOUBLE_EQ(v[0], v1);
  EXPECT_DOUBLE_EQ(x[0], 0.01 + 1e-3 * v1);
  ASSERT_NE(api.elastic_energy, nullptr);
  EXPECT_DOUBLE_EQ(api.elastic_energy(instance, x), 0.5 * 100.0 * x[0] * x[0]);
  api.destroy(instance);
}

}  // namespace
