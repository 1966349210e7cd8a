// Validation of the hyperelastic model: Neo-Hookean uniaxial tension at 50% stretch against the
// analytic homogeneous solution (static solve), the static cantilever converging under
// refinement toward Euler-Bernoulli, and recovery from an inverted start in dynamic steps.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <vector>

#include "cantilever_rows.hpp"
#include "hyperelastic_test_support.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::hyperelastic {
namespace {

using testing::Body;

TEST(HyperelasticValidation, NeoHookeanUniaxialTensionMatchesTheAnalyticStretch) {
  const double side = 0.1, stretch = 1.5;
  const testing::UniaxialResult r =
      testing::neo_hookean_uniaxial_patch(0.45, stretch, Volumetric::kElement);
  ASSERT_EQ(r.status & (TACTA_STEP_FAULT_MASK | TACTA_STEP_SOLVER_NOT_CONVERGED), 0u);
  std::printf(
      "uniaxial Neo-Hookean, stretch %.2f: P %.1f Pa, lateral stretch %.5f; worst node "
      "error %.2e m axial, %.2e m lateral; Newton iterations %llu, load cuts %llu\n",
      stretch, r.nominal_stress, r.lateral, r.worst_axial, r.worst_lateral,
      static_cast<unsigned long long>(r.newton_iterations),
      static_cast<unsigned long long>(r.load_cuts));
  EXPECT_LT(r.worst_axial, 0.01 * (stretch - 1.0) * side);  // within 1% of the elongation
  EXPECT_LT(r.worst_lateral, 0.01 * (1.0 - r.lateral) * side);
}

double static_cantilever_tip(std::array<uint32_t, 3> cells, MaterialLaw law) {
  const auto [tip, status] = testing::static_cantilever_tip(cells, law, 0.45, Volumetric::kElement);
  EXPECT_EQ(status & (TACTA_STEP_FAULT_MASK | TACTA_STEP_SOLVER_NOT_CONVERGED), 0u);
  return tip;
}

TEST(HyperelasticValidation, StaticCantileverConvergesUnderRefinement) {
  // Nodes 3x3x12, 5x5x30, 7x7x42; per-element volumes, so the same locking as corotational_fem.
  const std::array<double, 3> tips = {static_cantilever_tip({2, 2, 11}, MaterialLaw::kNeoHookean),
                                      static_cantilever_tip({4, 4, 29}, MaterialLaw::kNeoHookean),
                                      static_cantilever_tip({6, 6, 41}, MaterialLaw::kNeoHookean)};
  test::expect_cantilever_convergence("hyperelastic_neo_hookean", tips, {0.01477, 0.02538, 0.02805},
                                      {"3x3x12", "5x5x30", "7x7x42"});
}

TEST(HyperelasticValidation, DynamicStepsRecoverFromAnInvertedStart) {
  for (const MaterialLaw law : testing::all_laws()) {
    const TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
    auto model = testing::make_model(mesh, law, 1e4, 0.45, true);
    Body body(mesh);
    // The far corner pushed down through the top layer (off the diagonal, so that on its way
    // back it passes no node closely).
    const uint32_t top = mesh.node_count() - 1;
    body.x[3 * top + 0] = body.x[3 * top + 1] = 0.09;
    body.x[3 * top + 2] = 0.02;
    bool inverted_at_start = false;
    for (size_t t = 0; t < mesh.tets.size(); t += 4)
      inverted_at_start = inverted_at_start ||
                          tet_signed_volume(node_position(body.x.data(), mesh.tets[t]),
                                            node_position(body.x.data(), mesh.tets[t + 1]),
                                            node_position(body.x.data(), mesh.tets[t + 2]),
                                            node_position(body.x.data(), mesh.tets[t + 3])) < 0.0;
    ASSERT_TRUE(inverted_at_start);
    const double initial_energy = model->elastic_energy(body.x.data());
    model->begin(body.state, 1e-3);
    for (int step = 0; step < 2000; ++step)
      ASSERT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u)
          << testing::law_name(law) << " step " << step;
    // Restored: every element right side out and (the free body may keep spinning) almost all
    // the strain energy gone, dissipated by backward Euler.
    EXPECT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_INVERTED_ELEMENT, 0u)
        << testing::law_name(law);
    EXPECT_LT(model->elastic_energy(body.x.data()), 1e-3 * initial_energy)
        << testing::law_name(law);
  }
}

// tangent_reuse_steps: a soft clamped beam swinging down under gravity with Rayleigh stiffness
// damping (Kd lags with the tangent), stepped with a fresh tangent every step and with reuse:
// the tip follows the same path to 0.1% of its travel (the limit on F's change refreshes the
// tangent while the beam swings fast; without it 4 steps of lag gave 1.1%), and some first
// corrections reuse.
TEST(HyperelasticValidation, ReusedTangentFollowsTheFreshTangentPath) {
  TestMesh mesh = box_tet_mesh({2, 2, 10}, {0.02, 0.02, 0.2}, 1000.0);
  mesh.fix_plane(2, 0.0);
  tacta_material material = make_material(1e5, 0.45, 1000.0);
  material.rayleigh_mass = 1.0;
  material.rayleigh_stiffness = 0.01;
  std::vector<std::vector<double>> tips;
  std::vector<uint64_t> lagged;
  for (const int reuse : {0, 4}) {
    Options options;
    options.material = testing::material_for(MaterialLaw::kNeoHookean, 1e5, 0.45);
    options.volumetric = Volumetric::kNodalAverage;
    options.tangent_reuse_steps = reuse;
    HyperelasticModel model(mesh.view(), material, mesh.masses, mesh.fixed, options);
    Body body(mesh);
    for (uint32_t i = 0; i < mesh.node_count(); ++i) body.f[3 * i + 1] = -9.81 * mesh.masses[i];
    model.begin(body.state, 1e-3);
    std::vector<double> tip;
    for (int step = 0; step < 400; ++step) {
      ASSERT_EQ(model.step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u) << reuse << " " << step;
      tip.push_back(body.x[3 * (mesh.node_count() - 1) + 1] -
                    mesh.positions[3 * (mesh.node_count() - 1) + 1]);
    }
    tips.push_back(tip);
    lagged.push_back(model.counters().lagged_tangents);
  }
  double travel = 0.0, worst = 0.0;
  for (size_t k = 0; k < tips[0].size(); ++k) {
    travel = std::max(travel, std::abs(tips[0][k]));
    worst = std::max(worst, std::abs(tips[1][k] - tips[0][k]));
  }
  std::printf(
      "reused tangent: tip travel %.4f m, largest difference %.2e m, %llu of 400 first "
      "corrections reused\n",
      travel, worst, static_cast<unsigned long long>(lagged[1]));
  EXPECT_GT(travel, 0.01);
  EXPECT_LT(worst, 0.001 * travel);
  EXPECT_EQ(lagged[0], 0u);
  EXPECT_GT(lagged[1], 50u);
}

}  // namespace
}  // namespace tacta::models::hyperelastic
