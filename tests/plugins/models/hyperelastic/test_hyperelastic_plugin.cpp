// The hyperelastic plugin as a host sees it: loaded through the C ABI, created with default
// parameters on a clamped beam, stepped under gravity for each material, counters reported,
// and bad input refused with a message that names what is wrong.
#include <gtest/gtest.h>
#include <string>

#include "plugin_fixture.hpp"
#include "tacta/model_api.h"
#include "tacta/models/test_meshes.hpp"

namespace {

using tacta::testing::LoadedPlugin;

uint32_t index_of(const tacta_descriptor& d, const std::string& name) {
  for (uint32_t i = 0; i < d.param_count; ++i)
    if (name == d.params[i].name) return i;
  ADD_FAILURE() << "no parameter " << name;
  return 0;
}

TEST(HyperelasticPlugin, EveryMaterialStepsABeamUnderGravity) {
  LoadedPlugin plugin("tacta_hyperelastic.so");
  const tacta_descriptor& d = plugin.descriptor("hyperelastic");
  ASSERT_EQ(d.kind, TACTA_KIND_MODEL);
  const auto& api = plugin.api<tacta_model_api>("hyperelastic");
  ASSERT_NE(api.begin, nullptr);
  ASSERT_NE(api.elastic_energy, nullptr);
  ASSERT_NE(api.internal_forces, nullptr);
  ASSERT_NE(api.node_stress, nullptr);
  ASSERT_NE(api.counters, nullptr);
  ASSERT_GE(d.api_size, sizeof(tacta_model_api));
  for (const char* material : {"neo_hookean", "stvk", "mooney_rivlin"}) {
    SCOPED_TRACE(material);
    tacta::models::TestMesh mesh = tacta::models::box_tet_mesh({2, 2, 6}, {0.02, 0.02, 0.2}, 1100);
    mesh.fix_plane(2, 0.0);
    const tacta_mesh_view view = mesh.view();
    const tacta_material elastic = tacta::models::make_material(2e6, 0.45, 1100);
    auto params = tacta::testing::default_params(d);
    const uint32_t choice = index_of(d, "material");
    params[choice].text = material;
    params[choice].number = std::string(material) == "neo_hookean" ? 0
                            : std::string(material) == "stvk"      ? 1
                                                                   : 2;
    const tacta_model_setup setup = mesh.setup(view, elastic, params.data(), d.param_count, 1e-3);
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
    const uint32_t tip = mesh.node_count() - 1;
    EXPECT_LT(x[3 * tip + 1], mesh.positions[3 * tip + 1]);
    EXPECT_GT(api.elastic_energy(instance, x.data()), 0.0);
    api.node_stress(instance, x.data(), stress.data());
    EXPECT_GT(stress[0], 0.0);
    tacta_model_counter counters[32];
    const uint32_t count = api.counters(instance, counters, 32);
    ASSERT_GT(count, 0u);
    ASSERT_LE(count, 32u);
    EXPECT_EQ(std::string(counters[0].name), "steps");
    EXPECT_EQ(counters[0].value, 100.0);
    api.destroy(instance);
  }
}

TEST(HyperelasticPlugin, RefusesBadInputWithAMessage) {
  LoadedPlugin plugin("tacta_hyperelastic.so");
  const tacta_descriptor& d = plugin.descriptor("hyperelastic");
  const auto& api = plugin.api<tacta_model_api>("hyperelastic");
  tacta::models::TestMesh mesh = tacta::models::box_tet_mesh({1, 1, 2}, {0.02, 0.02, 0.04}, 1100);
  const tacta_mesh_view view = mesh.view();
  const tacta_material elastic = tacta::models::make_material(2e6, 0.45, 1100);
  auto params = tacta::testing::default_params(d);
  tacta_model_setup setup = mesh.setup(view, elastic, params.data(), d.param_count, 1e-3);
  void* instance = nullptr;
  char message[256] = {0};
  // A static solve with nothing held has no equilibrium under a net load.
  params[index_of(d, "solve")] = {1, "static", nullptr, 0};
  EXPECT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(message).find("static needs fixed nodes"), std::string::npos) << message;
  EXPECT_EQ(instance, nullptr);
  // A planar mesh has no tets.
  params = tacta::testing::default_params(d);
  setup.params = params.data();
  tacta::models::TestMesh square = tacta::models::quad_grid_mesh(1, 1, 1.0, 1.0, 1.0);
  const tacta_mesh_view square_view = square.view();
  setup.mesh = &square_view;
  setup.masses = square.masses.data();
  setup.fixed = square.fixed.data();
  EXPECT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(message).find("no tets"), std::string::npos) << message;
}

}  // namespace
