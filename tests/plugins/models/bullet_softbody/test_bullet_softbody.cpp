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
#include "validation_row.hpp"

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
  // create(), failing the test with the plugin's message when it refuses.
  void* create_or_fail(const TestMesh& mesh, const tacta_mesh_view& view) {
    char message[256] = {0};
    void* instance = create(mesh, view, message, sizeof message);
    EXPECT_NE(instance, nullptr) << message;
    return instance;
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
  // The undamped beam swings (period about 0.2 s): the tip's largest sag over the run, not its
  // phase at the end, shows that the free end moves.
  double tip = 0.0;
  for (int step = 0; step < 200; ++step) {
    ASSERT_EQ(run.api.step(instance, &state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
    for (uint32_t i = 0; i < mesh.node_count(); ++i)
      if (!mesh.fixed[i] && mesh.positions[3 * i + 2] > 0.19)
        tip = std::max(tip, mesh.positions[3 * i + 1] - x[3 * i + 1]);
  }
  for (uint32_t i = 0; i < mesh.node_count(); ++i)
    if (mesh.fixed[i]) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(x[3 * i + c], mesh.positions[3 * i + c]);
      EXPECT_EQ(v[3 * i + 1], 0.0);
    }
  EXPECT_GT(tip, 1e-4);  // the free end moved down
  // How far it sags against a reference: SettledCantileverTipWithinTwentyPercentOfMassSpring.
  std::printf("bullet cantilever tip, largest sag over 0.2 s: %.4f m\n", tip);
  run.api.destroy(instance);
}

// The settled tip of a damped cantilever (2x2x6 cells, SOFA's material, alpha 20/s, 1.5 s at
// 1 ms), Bullet against mass_spring with the same stiffness rule (van_gelder, both defaults).
// Reference: mass_spring, whose implicit steps settle on the same spring network's static
// equilibrium. Tolerance 20 %: a position projection is its spring only as x = k h^2 / m -> 0
// (at finite x the network is up to ln(1 + x) / x as stiff); the plugin's substeps keep x <= 1/16
// (measured 1.001x here; 1.86x before them and the held-node fix, whatever the iterations).
double settled_tip(const char* file, const char* name) {
  LoadedPlugin plugin(file);
  const tacta_descriptor& d = plugin.descriptor(name);
  const auto& api = plugin.api<tacta_model_api>(name);
  auto params = tacta::testing::default_params(d);
  TestMesh mesh = tacta::models::box_tet_mesh({2, 2, 6}, {0.02, 0.02, 0.2}, 1100.0);
  mesh.fix_plane(2, 0.0);
  tacta_material material = tacta::models::make_material(2e6, 0.45, 1100.0);
  material.rayleigh_mass = 20.0;
  const tacta_mesh_view view = mesh.view();
  const tacta_model_setup setup = mesh.setup(view, material, params.data(), d.param_count, 1e-3);
  void* instance = nullptr;
  char message[256] = {0};
  EXPECT_EQ(api.create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
  if (instance == nullptr) return 0.0;
  std::vector<double> x = mesh.positions, v(x.size(), 0.0), f(x.size(), 0.0);
  for (uint32_t i = 0; i < mesh.node_count(); ++i) f[3 * i + 1] = -9.81 * mesh.masses[i];
  tacta_body_state state{mesh.node_count(), x.data(), v.data(), f.data(), 0.0};
  if (api.begin != nullptr) api.begin(instance, &state, 1e-3);
  for (int i = 0; i < 1500; ++i)
    EXPECT_EQ(api.step(instance, &state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
  api.destroy(instance);
  return -mesh.mean_displacement_on_plane(x.data(), 2, 0.2, 1);
}

TEST(BulletSoftBody, SettledCantileverTipWithinTwentyPercentOfMassSpring) {
  const double bullet = settled_tip("tacta_bullet_softbody.so", "bullet_softbody");
  const double springs = settled_tip("tacta_mass_spring.so", "mass_spring");
  const bool pass = std::abs(bullet - springs) <= 0.2 * springs;
  tacta::test::validation_row("bullet_softbody.cantilever_vs_mass_spring",
                              "mass_spring's settled tip (same springs, exact solve), " +
                                  tacta::test::validation_number(springs) + " m",
                              "20 % (a projection is a spring only as k h^2 / m -> 0)",
                              tacta::test::validation_number(bullet) + " m (" +
                                  tacta::test::validation_number(bullet / springs, 3) + "x)",
                              pass);
  EXPECT_NEAR(bullet, springs, 0.2 * springs);
}

// A first step that starts deformed pulls back towards the rest shape (Bullet used to take the
// links' rest lengths from the first step's positions, so a body that started stretched stayed).
TEST(BulletSoftBody, FirstStepFromAStretchedStartPullsBack) {
  PluginRun run;
  const TestMesh mesh = tacta::models::box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  const tacta_mesh_view view = mesh.view();
  void* instance = run.create_or_fail(mesh, view);
  ASSERT_NE(instance, nullptr);
  std::vector<double> x = mesh.positions;
  for (double& c : x) c = 0.05 + 1.01 * (c - 0.05);  // 1 % about the centre
  std::vector<double> v(x.size(), 0.0), f(x.size(), 0.0);
  const std::vector<double> stretched = x;
  tacta_body_state state{mesh.node_count(), x.data(), v.data(), f.data(), 0.0};
  ASSERT_EQ(run.api.step(instance, &state, 1e-3), 0u);
  // Every corner node moves towards the centre.
  for (uint32_t i = 0; i < mesh.node_count(); ++i) {
    double before = 0, after = 0;
    for (int c = 0; c < 3; ++c) {
      before += std::pow(stretched[3 * i + c] - 0.05, 2);
      after += std::pow(x[3 * i + c] - 0.05, 2);
    }
    if (before > 3 * 0.05 * 0.05) {
      EXPECT_LT(after, before) << "node " << i;
    }
  }
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
