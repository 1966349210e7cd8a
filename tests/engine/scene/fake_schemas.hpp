// Hand-written plugin schemas for the scene loader tests, standing in for the real plugins (which
// are built elsewhere): the loader only needs names and parameter specs.
#pragma once

#include <gtest/gtest.h>
#include <initializer_list>
#include <string>

#include "tacta/scene_loader.hpp"
#include "tacta/sdk/common.hpp"

namespace tacta::testing {

using namespace tacta::sdk;

inline constexpr tacta_param_spec kCorotationalSchema[] = {
    choice_param("solver", "cg|cholesky|jacobi", 1, "linear solver"),
    int_param("iterations", 50, 1, 1000, "solver iterations per step"),
    real_param("tolerance", "", 1e-6, 1e-12, 0.1, "relative residual"),
    bool_param("lumped_mass", true, "diagonal mass matrix"),
    vector_param("gains", "", 3, "1 2 3", -10, 10, "per-axis gains"),
    text_param("cache_file", "cache.bin", "factorisation cache"),
};
inline constexpr tacta_param_spec kTensorMassSchema[] = {
    real_param("time_step", "s", 1e-3, 1e-6, 1e-2, "integration step"),
};
inline constexpr tacta_param_spec kMassSpringSchema[] = {
    real_param("spring_stiffness", "N/m", 100, 0, 1e9, "edge spring stiffness"),
    real_param("spring_damping", "N s/m", 0.1, 0, 1e6, "edge spring damping"),
};
inline constexpr tacta_param_spec kSimStylusSchema[] = {
    choice_param("trajectory", "press|circle|hold", 0, "scripted path"),
    real_param("depth", "m", 0.01, 0, 0.5, "press depth"),
    vector_param("start", "m", 3, "0 0.2 0", -10, 10, "start position"),
    real_param("max_force", "N", 3.3, 0, 100, "force limit"),
};
inline constexpr tacta_param_spec kReplaySchema[] = {
    text_param("file", "", "recorded trace (CSV)"),
};
inline constexpr tacta_param_spec kBvhSchema[] = {
    choice_param("volume", "aabb|obb", 0, "bounding volume"),
    int_param("leaf_size", 4, 1, 64, "primitives per leaf"),
};
inline constexpr tacta_param_spec kNoParams[] = {
    real_param("unused", "", 0, 0, 1, "placeholder so the array is not empty"),
};

inline const SchemaLookup& fake_schemas() {
  static const SchemaTable table = [] {
    SchemaTable t;
    t.add(TACTA_KIND_MODEL, "corotational_fem", kCorotationalSchema)
        .add(TACTA_KIND_MODEL, "tensor_mass", kTensorMassSchema)
        .add(TACTA_KIND_MODEL, "mass_spring", kMassSpringSchema)
        .add(TACTA_KIND_DEVICE, "sim_stylus", kSimStylusSchema)
        .add(TACTA_KIND_DEVICE, "replay", kReplaySchema)
        .add(TACTA_KIND_COLLISION, "bvh", kBvhSchema)
        .add(TACTA_KIND_COLLISION, "ccd", std::span<const tacta_param_spec>(kNoParams, 0))
        .add(TACTA_KIND_COLLISION, "convex", std::span<const tacta_param_spec>(kNoParams, 0));
    return t;
  }();
  return table;
}

// Raw string literals start with a newline for readability; line 1 is the line after it.
inline std::string yaml(const char* text) {
  std::string s(text);
  if (!s.empty() && s.front() == '\n') s.erase(0, 1);
  return s;
}

inline SceneDesc load(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return load_scene_from_string(text, "/scenes/test.yaml", fake_schemas(), overrides);
}

// The InputError that loading `text` throws; a test failure if it loads.
inline InputError load_error(const std::string& text,
                             const std::vector<std::string>& overrides = {}) {
  try {
    load(text, overrides);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "the scene loaded, but an InputError was expected";
  return InputError(SourceLocation{}, "no error");
}

// The error names the test scene's file, `line` and `key_path`, and says each fragment.
inline void expect_at(const InputError& e, int line, const std::string& key_path,
                      std::initializer_list<std::string> fragments) {
  EXPECT_EQ(e.where().file, "/scenes/test.yaml");
  EXPECT_EQ(e.where().line, line) << e.what();
  EXPECT_EQ(e.where().key_path, key_path) << e.what();
  const std::string message = e.what();
  for (const std::string& fragment : fragments)
    EXPECT_NE(message.find(fragment), std::string::npos)
        << "'" << fragment << "' not in: " << message;
}

// A small valid body used as the base of many tests.
inline const char* kMinimalScene = R"(
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [2, 2, 2]}}
    material: {youngs_modulus: 1.0e4, poisson_ratio: 0.3}
    model: tensor_mass
)";

}  // namespace tacta::testing
