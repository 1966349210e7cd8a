// bullet_softbody: loads through the C ABI, steps, falls under gravity, keeps fixed nodes, and
// the documented E -> kLST rule behaves (in (0, 1], stiffer material gives a larger kLST, and
// n iterations close what one implicit step of the link's spring would).
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <string>

#include "bullet_softbody.hpp"
#include "plugin_fixture.hpp"
#include "tacta/model_api.h"
#include "tacta/models/spring_stiffness.hpp"
#include "tacta/models/test_meshes.hpp"

namespace {

using tacta::models::TestMesh;
using tacta::testing::LoadedPlugin;

struct PluginRun {
  LoadedPlugin plugin{"tacta_bullet_softbody.so"};
  const tacta_descriptor& descriptor = plugin.descriptor("bullet_softbody");
  const tacta_model_api& api = plugin.api<tacta_model_api>("bullet_softbody");
  tacta::testing::DefaultParams params = tacta::testing::default_params(descriptor);
  tacta_material material = tacta::models::make_material(1e5, 0.3, 1000.0);

  void* create(const TestMesh& mesh, const tacta_mesh_view& view, char* message, size_t size) {
    tacta_model_setup setup =
        mesh.setup(view, material, params.data(), descriptor.param_count, 1e-3);
    void* instance = nullptr;
    const tacta_status status = api.create(&setup, &instance, message, size);
    return status == TACTA_OK ? instance : nullptr;
  }
};

TEST(BulletSoftBody, SchemaNamesItsParameters) {
  PluginRun run;
  ASSERT_EQ(run.descriptor.kind, TACTA_KIND_MODEL);
  ASSERT_EQ(run.descriptor.param_count, 4u);
  EXPECT_STREQ(run.descriptor.params[0].name, "position_iterations");
  EXPECT_STREQ(run.descriptor.params[1].name, "stiffness_override");
  EXPECT_STREQ(run.descriptor.params[2].name, "bending");
  EXPECT_STREQ(run.descriptor.params[3].name, "stiffness_rule");
}

TEST(BulletSoftBody, FreeBodyFallsUnderGravity) {
  PluginRun run;
  const TestMesh mesh = tacta::models::box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  const tacta_mesh_view view = mesh.view();
  char message[256] = {0};
  void* instance = run.create(mesh, view, message, sizeof message);
  ASSERT_NE(instance, nullptr) << message;
  std::vector<double> x = mesh.positions, v(x.size(), 0.0), f(x.size(), 0.0);
  for (uint32_t i = 0; i < mesh.node_count(); ++i) f[3 * i + 1] = -9.81 * mesh.masses[i];
  tacta_body_state state{mesh.node_count(), x.data(), v.data(), f.data(), 0.0};
  const double dt = 1e-3;
  for (int i = 0; i < 100; ++i) ASSERT_EQ(run.api.step(instance, &state, dt), 0u);
  // Free fall for t = 0.1 s: every node drops g t^2 / 2 = 0.049 m (semi-implicit Euler gives
  // g t (t + dt) / 2) and keeps the body's shape.
  const double t = 100 * dt, expected = 9.81 * t * (t + dt) / 2;
  for (uint32_t i = 0; i < mesh.node_count(); ++i) {
    EXPECT_NEAR(mesh.positions[3 * i + 1] - x[3 * i + 1], expected, 0.02 * expected);
    EXPECT_NEAR(x[3 * i], mesh.positions[3 * i], 1e-9);
    EXPECT_NEAR(v[3 * i + 1], -9.81 * t, 0.02 * 9.81 * t);
  }
  run.api.destroy(instance);
}

TEST(BulletSoftBody, FixedNodesStayWhileTheRestSags) {
  PluginRun run;
  TestMesh mesh = tacta::models::box_tet_mesh({2, 2, 6}, {0.02, 0.02, 0.2}, 1100.0);
  mesh.fix_plane(2, 0.0);
  run.material = tacta::models::make_material(2e6, 0.45, 1100.0);  // SOFA's cantilever
  const tacta_mesh_view view = mesh.view();
  char message[256] = {0};
  void* instance = run.create(mesh, view, message, sizeof message);
  ASSERT_NE(instance, nullptr) << message;
  std::vector<double> x = mesh.positions, v(x.size(), 0.0), f(x.size(), 0.0);
  for (uint32_t i = 0; i < mesh.node_count(); ++i) f[3 * i + 1] = -9.81 * mesh.masses[i];
  tacta_body_state state{mesh.node_count(), x.data(), v.data(), f.data(), 0.0};
  for (int i = 0; i < 200; ++i)
    ASSERT_EQ(run.api.step(instance, &state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
  double tip = 0.0;
  for (uint32_t i = 0; i < mesh.node_count(); ++i) {
    if (mesh.fixed[i]) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(x[3 * i + c], mesh.positions[3 * i + c]);
      EXPECT_EQ(v[3 * i + 1], 0.0);
    } else if (mesh.positions[3 * i + 2] > 0.19) {
      tip = std::max(tip, mesh.positions[3 * i + 1] - x[3 * i + 1]);
    }
  }
  EXPECT_GT(tip, 1e-4);  // the free end moved down
  // A free fall over the 0.2 s would be 0.196 m; the static elastic answer is about 0.03 m.
  std::printf("bullet cantilever tip after 0.2 s: %.4f m\n", tip);
  EXPECT_LT(tip, 0.15);  // links hold the beam
  run.api.destroy(instance);
}

TEST(BulletSoftBody, RejectsFreeNodeWithoutMass) {
  PluginRun run;
  TestMesh mesh = tacta::models::box_tet_mesh({1, 1, 1}, {0.1, 0.1, 0.1}, 1000.0);
  mesh.masses[7] = 0.0;
  const tacta_mesh_view view = mesh.view();
  char message[256] = {0};
  EXPECT_EQ(run.create(mesh, view, message, sizeof message), nullptr);
  EXPECT_NE(std::string(message).find("node 7"), std::string::npos) << message;
}

TEST(BulletSoftBody, StiffnessRuleIsMonotoneAndBounded) {
  const TestMesh mesh = tacta::models::box_tet_mesh({3, 3, 3}, {0.1, 0.1, 0.1}, 1000.0);
  const tacta_mesh_view view = mesh.view();
  using tacta::models::StiffnessRule;
  for (StiffnessRule rule : {StiffnessRule::kVanGelder, StiffnessRule::kFemProjection}) {
    std::vector<double> previous(mesh.edges.size() / 2, 0.0);
    for (double e : {1e2, 1e3, 1e4, 1e5, 1e6}) {
      const std::vector<double> k = tacta::models::bullet::link_stiffness_from_material(
          view, mesh.masses, tacta::models::make_material(e, 0.3, 1000.0), rule, 1e-3, 10);
      ASSERT_EQ(k.size(), previous.size());
      for (size_t link = 0; link < k.size(); ++link) {
        EXPECT_GT(k[link], previous[link]) << "E = " << e << ", link " << link;
        EXPECT_LE(k[link], 1.0);
      }
      previous = k;
    }
  }
}

TEST(BulletSoftBody, LinkFractionClosesTheImplicitSpringsShareOverTheIterations) {
  // n iterations of kLST close what one implicit step of the Van Gelder spring would:
  // 1 - (1 - kLST)^n = k dt^2 / (m_reduced + k dt^2), link by link.
  const TestMesh mesh = tacta::models::box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  const tacta_mesh_view view = mesh.view();
  const tacta_material material = tacta::models::make_material(1e5, 0.3, 1000.0);
  const double dt = 1e-3;
  const int iterations = 7;
  const auto fraction = tacta::models::bullet::link_stiffness_from_material(
      view, mesh.masses, material, tacta::models::StiffnessRule::kVanGelder, dt, iterations);
  const auto spring = tacta::models::edge_stiffness("test", view, material,
                                                    tacta::models::StiffnessRule::kVanGelder);
  for (size_t e = 0; e < spring.size(); ++e) {
    const double ma = mesh.masses[mesh.edges[2 * e]], mb = mesh.masses[mesh.edges[2 * e + 1]];
    const double reduced = ma * mb / (ma + mb), kdt2 = spring[e] * dt * dt;
    EXPECT_NEAR(1 - std::pow(1 - fraction[e], iterations), kdt2 / (reduced + kdt2), 1e-12) << e;
  }
}

}  // namespace
