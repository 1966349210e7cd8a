// mass_spring through the real C ABI: each integrator created and stepped from default params.
#include <gtest/gtest.h>
#include <string>

#include "plugin_fixture.hpp"
#include "tacta/model_api.h"
#include "tacta/models/test_meshes.hpp"

using namespace tacta::models;

TEST(MassSpringPlugin, LoadsCreatesAndStepsEachIntegrator) {
  tacta::testing::LoadedPlugin plugin("tacta_mass_spring.so");
  const tacta_descriptor& d = plugin.descriptor("mass_spring");
  EXPECT_STREQ(d.params[0].choices, "symplectic_euler|implicit_euler|desbrun");
  const auto& api = plugin.api<tacta_model_api>("mass_spring");
  TestMesh mesh = box_tet_mesh({3, 1, 1}, {0.3, 0.1, 0.1}, 1000.0);
  mesh.fix_plane(0, 0.0);
  const tacta_mesh_view view = mesh.view();
  const tacta_material material = make_material(1e5, 0.3, 1000.0);
  for (double integrator : {0.0, 1.0, 2.0}) {
    auto params = tacta::testing::default_params(d);
    params[0].number = integrator;
    tacta_model_setup setup = mesh.setup(view, material, params.data(), d.param_count, 1e-4);
    void* instance = nullptr;
    char message[256] = {0};
    ASSERT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
    std::vector<double> x = mesh.positions, v(x.size(), 0.0), f(x.size(), 0.0);
    for (size_t i = 2; i < f.size(); i += 3) f[i] = -9.81 * mesh.masses[i / 3];
    tacta_body_state state{mesh.node_count(), x.data(), v.data(), f.data(), 0.0};
    for (int k = 0; k < 200; ++k) ASSERT_EQ(api.step(instance, &state, 1e-4), TACTA_STEP_OK);
    EXPECT_LT(x[3 * 3 + 2], 0.0) << integrator;  // the free end sags
    EXPECT_GT(api.elastic_energy(instance, x.data()), 0.0);
    api.destroy(instance);
  }
  // A mesh without tets is refused with a reason.
  TestMesh edges_only = grid_edge_mesh({2, 1, 1}, {0.2, 0.1, 0.1}, 1000.0);
  const tacta_mesh_view bad = edges_only.view();
  auto params = tacta::testing::default_params(d);
  tacta_model_setup setup = edges_only.setup(bad, material, params.data(), d.param_count, 1e-4);
  void* instance = nullptr;
  char message[256] = {0};
  EXPECT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(message).find("tetrahedral"), std::string::npos);
}
