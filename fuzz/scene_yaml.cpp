// Fuzzes the scene loader with overrides: leading lines "--set key.path=value" are the command
// line's overrides, the rest is the scene's YAML. Plugin schemas are a fixed table under the real
// plugin names with every parameter type, so that plugin parameters get validated too.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tacta/scene_loader.hpp"
#include "tacta/sdk/common.hpp"

namespace {

using namespace tacta::sdk;

constexpr tacta_param_spec kModelSchema[] = {
    choice_param("solver", "cg|cholesky|jacobi", 0, "linear solver"),
    int_param("iterations", 50, 1, 1000, "solver iterations per step"),
    real_param("damping", "1/s", 0.1, 0, 1e3, "mass damping"),
    bool_param("lumped_mass", true, "diagonal mass matrix"),
};
constexpr tacta_param_spec kDeviceSchema[] = {
    vector_param("workspace_origin", "m", 3, "0 0 0", -1e3, 1e3, "centre of the workspace"),
    vector_param("waypoints", "s, m", 4, "", -1e3, 1e3, "t x y z per waypoint"),
    text_param("log", "", "device log"),
    real_param("time_offset", "s", 0, -1e6, 1e6, "engine time = log time + offset"),
    bool_param("loop", false, "loop the log"),
};
constexpr tacta_param_spec kCollisionSchema[] = {
    choice_param("volume", "aabb|obb", 0, "bounding volume"),
    int_param("leaf_size", 4, 1, 64, "primitives per leaf"),
};

const tacta::SchemaLookup& schemas() {
  static const tacta::SchemaTable table = [] {
    tacta::SchemaTable t;
    for (const char* model :
         {"corotational_fem", "tensor_mass", "mass_spring", "fd_debunne", "bullet_softbody"})
      t.add(TACTA_KIND_MODEL, model, kModelSchema);
    for (const char* device : {"sim_stylus", "replay", "mouse", "openigtlink", "net"})
      t.add(TACTA_KIND_DEVICE, device, kDeviceSchema);
    for (const char* collision : {"bvh", "ccd", "convex"})
      t.add(TACTA_KIND_COLLISION, collision, kCollisionSchema);
    return t;
  }();
  return table;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> overrides;
  constexpr std::string_view kSet = "--set ";
  while (text.starts_with(kSet)) {
    const size_t end = text.find('\n');
    overrides.emplace_back(text.substr(
        kSet.size(), end == std::string_view::npos ? std::string_view::npos : end - kSet.size()));
    text.remove_prefix(end == std::string_view::npos ? text.size() : end + 1);
  }
  try {
    (void)tacta::load_scene_from_string(std::string(text), "/fuzz/scene.yaml", schemas(),
                                        overrides);
  } catch (const tacta::InputError&) {
  }
  return 0;
}
