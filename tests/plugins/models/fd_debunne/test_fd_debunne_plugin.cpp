// fd_debunne through the real C ABI: load the .so, check the schema, create, step, destroy.
#include <gtest/gtest.h>
#include <string>

#include "plugin_fixture.hpp"
#include "tacta/model_api.h"
#include "tacta/models/test_meshes.hpp"

using namespace tacta::models;

TEST(FdDebunnePlugin, LoadsCreatesAndSteps) {
  tacta::testing::LoadedPlugin plugin("tacta_fd_debunne.so");
  const tacta_descriptor& d = plugin.descriptor("fd_debunne");
  ASSERT_EQ(d.kind, TACTA_KIND_MODEL);
  std::vector<std::string> names;
  for (uint32_t i = 0; i < d.param_count; ++i) names.emplace_back(d.params[i].name);
  EXPECT_EQ(names, (std::vector<std::string>{"integrator", "damping", "symmetric", "operator_scale",
                                             "divergence_stretch"}));
  const auto& api = plugin.api<tacta_model_api>("fd_debunne");
  ASSERT_NE(api.internal_forces, nullptr);
  ASSERT_NE(api.elastic_energy, nullptr);

  TestMesh mesh = quad_grid_mesh(1, 1, 1.0, 1.0, 1.0);
  const tacta_mesh_view view = mesh.view();
  const tacta_material material = make_material_lame(1.0, 0.01, 1.0);
  auto params = tacta::testing::default_params(d);
  tacta_model_setup setup = mesh.setup(view, material, params.data(), d.param_count, 0.01);
  void* instance = nullptr;
  char message[256] = {0};
  ASSERT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
  std::vector<double> x = mesh.positions, v(x.size(), 0.0), f(x.size(), 0.0);
  x[9] -= 0.1, x[10] -= 0.1;  // NE corner
  tacta_body_state state{4, x.data(), v.data(), f.data(), 0.0};
  EXPECT_GT(api.elastic_energy(instance, x.data()), 0.0);
  for (int k = 0; k < 100; ++k) ASSERT_EQ(api.step(instance, &state, 0.01), TACTA_STEP_OK);
  EXPECT_GT(x[9], 1.0 - 0.1);  // NE corner pulled back toward its rest position
  api.destroy(instance);

  // Bad input: a mesh without edges is refused with a message, not a crash.
  tacta_mesh_view empty = view;
  empty.edge_count = 0;
  setup.mesh = &empty;
  EXPECT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(message).find("edges"), std::string::npos);
}
