// The corotational_fem plugin as a host sees it: loaded through the C ABI, schema checked,
// created with default parameters, stepped under gravity; bad input gives a message.
#include <gtest/gtest.h>
#include <string>

#include "plugin_fixture.hpp"
#include "tacta/model_api.h"
#include "tacta/models/test_meshes.hpp"

namespace {

using tacta::testing::LoadedPlugin;

// A 2 x 2 x 6-cell cantilever (0.02 x 0.02 x 0.2 m, E 2 MPa, clamped at z = 0) and the setup
// that creates the plugin's instance on it with its default parameters. The setup points into
// the members: built in place, never moved.
struct Cantilever {
  explicit Cantilever(const tacta_descriptor& d)
      : mesh(fixed_root(tacta::models::box_tet_mesh({2, 2, 6}, {0.02, 0.02, 0.2}, 1100))),
        view(mesh.view()),
        material(tacta::models::make_material(2e6, 0.45, 1100)),
        params(tacta::testing::default_params(d)),
        setup(mesh.setup(view, material, params.data(), d.param_count, 1e-3)) {}
  Cantilever(const Cantilever&) = delete;
  Cantilever& operator=(const Cantilever&) = delete;
  static tacta::models::TestMesh fixed_root(tacta::models::TestMesh m) {
    m.fix_plane(2, 0.0);
    return m;
  }
  tacta::models::TestMesh mesh;
  tacta_mesh_view view;
  tacta_material material;
  tacta::testing::DefaultParams params;
  tacta_model_setup setup;
};

TEST(CorotationalPlugin, LoadsCreatesAndSteps) {
  LoadedPlugin plugin("tacta_corotational_fem.so");
  const tacta_descriptor& d = plugin.descriptor("corotational_fem");
  ASSERT_EQ(d.kind, TACTA_KIND_MODEL);
  std::vector<std::string> names;
  for (uint32_t i = 0; i < d.param_count; ++i) names.emplace_back(d.params[i].name);
  EXPECT_EQ(names, (std::vector<std::string>{"rotation", "solver", "preconditioner",
                                             "max_iterations", "tolerance", "refactor_interval",
                                             "fallback", "restart_factor", "solve", "load_steps",
                                             "static_iterations", "static_tolerance", "guess",
                                             "tolerance_scale", "threaded_solve"}));
  const auto& api = plugin.api<tacta_model_api>("corotational_fem");
  ASSERT_NE(api.elastic_energy, nullptr);
  ASSERT_NE(api.internal_forces, nullptr);
  ASSERT_NE(api.node_stress, nullptr);
  ASSERT_NE(api.begin, nullptr);
  ASSERT_NE(api.counters, nullptr);

  Cantilever beam(d);
  tacta::models::TestMesh& mesh = beam.mesh;
  tacta_model_setup& setup = beam.setup;
  void* instance = nullptr;
  char message[256] = {0};
  ASSERT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
  std::vector<double> x = mesh.positions, v(x.size(), 0.0), f(x.size(), 0.0),
                      stress(mesh.node_count());
  for (uint32_t i = 0; i < mesh.node_count(); ++i) f[3 * i + 1] = -9.81 * mesh.masses[i];
  tacta_body_state state{mesh.node_count(), x.data(), v.data(), f.data(), 0.0};
  api.begin(instance, &state, 1e-3);
  for (int i = 0; i < 100; ++i)
    ASSERT_EQ(api.step(instance, &state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
  EXPECT_LT(x[3 * (mesh.node_count() - 1) + 1], mesh.positions[3 * (mesh.node_count() - 1) + 1]);
  EXPECT_GT(api.elastic_energy(instance, x.data()), 0.0);
  api.node_stress(instance, x.data(), stress.data());
  EXPECT_GT(stress[0], 0.0);  // the clamped root is where bending stress peaks
  api.destroy(instance);

  const uint32_t last = mesh.node_count() - 1;
  mesh.masses[last] = -1.0;  // a free node with negative mass: refused with the node named
  instance = nullptr;
  EXPECT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(message).find("node " + std::to_string(last)), std::string::npos)
      << message;
  EXPECT_EQ(instance, nullptr);
}

// set_param changes the solver's limits while running (seen in the step's not-converged bit)
// and refuses what would need new buffers, out-of-range values and unknown indices.
TEST(CorotationalPlugin, SetParamChangesSolverLimitsOnly) {
  LoadedPlugin plugin("tacta_corotational_fem.so");
  const tacta_descriptor& d = plugin.descriptor("corotational_fem");
  const auto& api = plugin.api<tacta_model_api>("corotational_fem");
  ASSERT_NE(api.set_param, nullptr);
  Cantilever beam(d);
  tacta::models::TestMesh& mesh = beam.mesh;
  tacta_model_setup& setup = beam.setup;
  void* instance = nullptr;
  char message[256] = {0};
  ASSERT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
  std::vector<double> x = mesh.positions, v(x.size(), 0.0), f(x.size(), 0.0);
  for (uint32_t i = 0; i < mesh.node_count(); ++i) f[3 * i + 1] = -9.81 * mesh.masses[i];
  tacta_body_state state{mesh.node_count(), x.data(), v.data(), f.data(), 0.0};
  api.begin(instance, &state, 1e-3);
  auto index_of = [&](const std::string& name) {
    for (uint32_t i = 0; i < d.param_count; ++i)
      if (name == d.params[i].name) return i;
    ADD_FAILURE() << name;
    return 0u;
  };
  auto set = [&](const std::string& name, double number) {
    tacta_param_value value{number, nullptr, nullptr, 0};
    return api.set_param(instance, index_of(name), &value, message, sizeof message);
  };
  // One CG iteration to 1e-14 cannot converge, nor can its restart (8): the step falls back
  // to LDL^T (seen in the counters) and converges; 500 to 1e-6 need no fallback.
  auto counter = [&](const std::string& name) {
    tacta_model_counter counters[32];
    const uint32_t count = api.counters(instance, counters, 32);
    for (uint32_t i = 0; i < count && i < 32; ++i)
      if (name == counters[i].name) return counters[i].value;
    ADD_FAILURE() << "no counter " << name;
    return -1.0;
  };
  ASSERT_EQ(set("max_iterations", 1), TACTA_OK) << message;
  ASSERT_EQ(set("tolerance", 1e-14), TACTA_OK) << message;
  EXPECT_EQ(api.step(instance, &state, 1e-3) & TACTA_STEP_SOLVER_NOT_CONVERGED, 0u);
  EXPECT_EQ(counter("direct_fallbacks"), 1.0);
  EXPECT_EQ(counter("cg_restarts"), 1.0);
  ASSERT_EQ(set("max_iterations", 500), TACTA_OK) << message;
  ASSERT_EQ(set("tolerance", 1e-6), TACTA_OK) << message;
  for (int i = 0; i < 2; ++i)  // the first goes straight to LDL^T (held after the fallback)
    EXPECT_EQ(api.step(instance, &state, 1e-3) & TACTA_STEP_SOLVER_NOT_CONVERGED, 0u);
  EXPECT_EQ(counter("direct_fallbacks"), 1.0);
  EXPECT_EQ(counter("direct_solves_held"), 1.0);
  EXPECT_EQ(counter("unconverged_solves"), 0.0);
  EXPECT_EQ(set("refactor_interval", 4), TACTA_OK) << message;

  EXPECT_NE(set("rotation", 1), TACTA_OK);
  EXPECT_NE(std::string(message).find("'rotation' cannot change"), std::string::npos) << message;
  EXPECT_NE(set("tolerance", 2.0), TACTA_OK);
  EXPECT_NE(std::string(message).find("tolerance"), std::string::npos) << message;
  EXPECT_NE(set("max_iterations", 2.5), TACTA_OK);
  tacta_param_value value{1.0, nullptr, nullptr, 0};
  EXPECT_NE(api.set_param(instance, d.param_count, &value, message, sizeof message), TACTA_OK);
  api.destroy(instance);
}

}  // namespace
