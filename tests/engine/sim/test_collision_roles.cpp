// Collision roles: the in-tree plugins declare theirs, a plugin built without the `roles` member
// has them guessed from its entries and still serves, a scene names the plugin per role
// (collision.plugins) and one lacking the role is refused at the key's line, and report.json
// says which plugin serves which role.
#include <dlfcn.h>
#include <nlohmann/json.hpp>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

uint32_t roles_of(const std::string& name, bool& guessed) {
  const LoadedDescriptor* d = plugins().find(TACTA_KIND_COLLISION, name);
  EXPECT_NE(d, nullptr) << name;
  if (d == nullptr) return 0;
  int g = 0;
  const uint32_t roles = tacta_collision_roles(d->descriptor, &g);
  guessed = g != 0;
  return roles;
}

// The cube press with its collision section replaced by `collision` (YAML lines).
std::string cube_press_with(const std::string& collision) {
  std::string text = kCubePressScene;
  const std::string old = "collision: {broad_phase: bvh}   # answers the proxy's surface queries\n";
  text.replace(text.find(old), old.size(), collision);
  return text;
}

int line_of(const std::string& text, const std::string& what) {
  const size_t at = text.find(what);
  return 1 + static_cast<int>(
                 std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

nlohmann::json read_report(const std::string& dir) {
  std::ifstream in(dir + "/report.json");
  return nlohmann::json::parse(in);
}

TEST(CollisionRoles, InTreePluginsDeclareTheirRoles) {
  bool guessed = true;
  EXPECT_EQ(roles_of("bvh", guessed),
            TACTA_COLLISION_ROLE_BROAD_PHASE | TACTA_COLLISION_ROLE_PROXY);
  EXPECT_FALSE(guessed);
  EXPECT_EQ(roles_of("ccd", guessed),
            TACTA_COLLISION_ROLE_NARROW_PHASE | TACTA_COLLISION_ROLE_RESPONSE);
  EXPECT_FALSE(guessed);
  EXPECT_EQ(roles_of("convex", guessed), TACTA_COLLISION_ROLE_NARROW_PHASE);
  EXPECT_FALSE(guessed);
}

TEST(CollisionRoles, PluginWithoutRolesFallsBackToItsEntries) {
  bool guessed = false;
  EXPECT_EQ(roles_of("test_legacy_response", guessed), TACTA_COLLISION_ROLE_RESPONSE);
  EXPECT_TRUE(guessed);
  // A table with the member present but 0 is guessed the same way.
  tacta_collision_api api{};
  api.find_pairs = plugins().find(TACTA_KIND_COLLISION, "bvh") != nullptr
                       ? static_cast<const tacta_collision_api*>(
                             plugins().find(TACTA_KIND_COLLISION, "bvh")->descriptor->api)
                             ->find_pairs
                       : nullptr;
  tacta_descriptor d{};
  d.api = &api;
  d.api_size = sizeof api;
  int g = 0;
  EXPECT_EQ(tacta_collision_roles(&d, &g), TACTA_COLLISION_ROLE_BROAD_PHASE);
  EXPECT_EQ(g, 1);

  // The guessed plugin serves the role a scene names it for, end to end.
  const std::string text =
      cube_press_with("collision:\n  plugins: {response: test_legacy_response}\n");
  const std::string out = fresh_dir("legacy_response");
  RunOptions options;
  options.out_dir = out;
  const RunResult r = run_scene(scene_from_text(text, "legacy_response"), options);
  EXPECT_EQ(r.exit_code, 0);
  using Calls = long (*)();
  // The registry loaded it already: NOLOAD finds that copy (its symbols are local to it).
  const std::string path =
      std::string(TACTA_SIM_TEST_PLUGIN_DIR) + "/tacta_test_legacy_response.so";
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD);
  ASSERT_NE(handle, nullptr) << path;
  auto calls = reinterpret_cast<Calls>(dlsym(handle, "tacta_test_legacy_response_calls"));
  dlclose(handle);
  ASSERT_NE(calls, nullptr);
  EXPECT_GT(calls(), 0) << "the named response plugin was never called";
  const nlohmann::json report = read_report(out);
  EXPECT_EQ(report["collision"]["roles"]["response"], "test_legacy_response");
  EXPECT_EQ(report["collision"]["roles"]["narrow_phase"], "ccd");
  bool listed = false;
  for (const auto& p : report["collision"]["plugins"])
    if (p["name"] == "test_legacy_response") {
      listed = true;
      EXPECT_TRUE(p["roles_guessed"].get<bool>());
      EXPECT_EQ(p["serves"], nlohmann::json::array({"response"}));
    }
  EXPECT_TRUE(listed);
}

TEST(CollisionRoles, PluginLackingTheNamedRoleIsRefusedAtItsLine) {
  const std::string text =
      cube_press_with("collision:\n  plugins:\n    broad_phase: test_legacy_response\n");
  const SceneDesc scene = scene_from_text(text, "role_refused");
  try {
    Simulation simulation(scene, plugins());
    FAIL() << "a response-only plugin was accepted as the broad phase";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, scene_path("role_refused"));
    EXPECT_EQ(e.where().line, line_of(text, "broad_phase: test_legacy_response"));
    EXPECT_NE(std::string(e.what()).find("does not declare the broad_phase role"),
              std::string::npos)
        << e.what();
  }
}

TEST(CollisionRoles, UnknownRoleKeyIsRefused) {
  const std::string text = cube_press_with("collision:\n  plugins: {responder: ccd}\n");
  EXPECT_THROW(scene_from_text(text, "role_key"), InputError);
}

TEST(CollisionRoles, ReportSaysWhichPluginServesWhichRole) {
  const std::string text = cube_press_with("collision: {thickness: 1.0e-4}\n");
  const std::string out = fresh_dir("roles_report");
  RunOptions options;
  options.out_dir = out;
  run_scene(scene_from_text(text, "roles_report"), options);
  const nlohmann::json c = read_report(out)["collision"];
  EXPECT_EQ(c["roles"]["broad_phase"], "bvh");
  EXPECT_EQ(c["roles"]["proxy"], "bvh");
  EXPECT_EQ(c["roles"]["narrow_phase"], "ccd");
  EXPECT_EQ(c["roles"]["response"], "ccd");
  EXPECT_GT(c["capacity"]["contacts"].get<uint64_t>(), 0u);
}

}  // namespace
}  // namespace tacta::simtest
