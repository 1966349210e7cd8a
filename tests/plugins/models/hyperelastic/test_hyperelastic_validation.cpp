// Validation of the hyperelastic model: Neo-Hookean uniaxial tension at 50% stretch against the
// analytic homogeneous solution (static solve), the static cantilever converging under
// refinement toward Euler-Bernoulli, and recovery from an inverted start in dynamic steps.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "hyperelastic_test_support.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::hyperelastic {
namespace {

using testing::material_for;

struct Body {  // the arrays the engine would own
  std::vector<double> x, v, f;
  tacta_body_state state{};
  explicit Body(const TestMesh& mesh) : x(mesh.positions), v(x.size(), 0.0), f(x.size(), 0.0) {
    state = {mesh.node_count(), x.data(), v.data(), f.data(), 0.0};
  }
};

// Compressible Neo-Hookean under uniaxial stress: principal stretches (s, t, t) with zero
// lateral stress, mu t + (lambda ln J - mu) / t = 0, J = s t^2. Returns t and the nominal
// (first Piola-Kirchhoff) axial stress P = mu s + (lambda ln J - mu) / s, Pa.
std::pair<double, double> neo_hookean_uniaxial(double mu, double lambda, double s) {
  double t = 1.0;
  for (int i = 0; i < 50; ++i) {  // Newton on the lateral equation
    const double log_j = std::log(s * t * t);
    const double g = mu * t + (lambda * log_j - mu) / t;
    const double dg = mu + (2.0 * lambda - lambda * log_j + mu) / (t * t);
    t -= g / dg;
  }
  return {t, mu * s + (lambda * std::log(s * t * t) - mu) / s};
}

TEST(HyperelasticValidation, NeoHookeanUniaxialTensionMatchesTheAnalyticStretch) {
  const double side = 0.1, e = 1e4, nu = 0.45, stretch = 1.5;
  const MaterialConstants m = material_for(MaterialLaw::kNeoHookean, e, nu);
  const auto [lateral, nominal_stress] = neo_hookean_uniaxial(m.mu, m.lambda, stretch);
  TestMesh mesh = box_tet_mesh({2, 2, 4}, {side, side, side}, 1000.0);
  mesh.fix_plane(2, 0.0);
  Options options;
  options.mode = SolveMode::kStatic;
  options.solver.solver = sparse::LinearSolver::kCholesky;
  auto model = testing::make_model(mesh, MaterialLaw::kNeoHookean, e, nu, true, options);
  Body body(mesh);
  // The held base takes the analytic lateral contraction about the corner (0, 0, 0); the top
  // face carries the nominal stress as consistent nodal forces (a third of each face's area).
  for (uint32_t i = 0; i < mesh.node_count(); ++i)
    if (mesh.fixed[i])
      for (int c = 0; c < 2; ++c) body.x[3 * i + c] *= lateral;
  for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
    const uint32_t* tri = &mesh.triangles[t];
    bool top = true;
    for (int k = 0; k < 3; ++k) top = top && mesh.positions[3 * tri[k] + 2] > side - 1e-12;
    if (!top) continue;
    const Eigen::Vector3d a = node_position(mesh.positions.data(), tri[0]);
    const Eigen::Vector3d b = node_position(mesh.positions.data(), tri[1]);
    const Eigen::Vector3d c = node_position(mesh.positions.data(), tri[2]);
    const double area = 0.5 * (b - a).cross(c - a).norm();
    for (int k = 0; k < 3; ++k) body.f[3 * tri[k] + 2] += nominal_stress * area / 3.0;
  }
  model->begin(body.state, 1.0);
  ASSERT_EQ(model->step(body.state, 1.0) & (TACTA_STEP_FAULT_MASK | TACTA_STEP_SOLVER_NOT_CONVERGED), 0u);
  double worst_axial = 0.0, worst_lateral = 0.0;
  for (uint32_t i = 0; i < mesh.node_count(); ++i) {
    worst_axial = std::max(worst_axial, std::abs(body.x[3 * i + 2] - stretch * mesh.positions[3 * i + 2]));
    for (int c = 0; c < 2; ++c)
      worst_lateral = std::max(worst_lateral, std::abs(body.x[3 * i + c] - lateral * mesh.positions[3 * i + c]));
  }
  const auto& counters = model->counters();
  std::printf("uniaxial Neo-Hookean, stretch %.2f: P %.1f Pa, lateral stretch %.5f; worst node "
              "error %.2e m axial, %.2e m lateral; Newton iterations %llu, load cuts %llu\n",
              stretch, nominal_stress, lateral, worst_axial, worst_lateral,
              static_cast<unsigned long long>(counters.newton_iterations),
              static_cast<unsigned long long>(counters.load_cuts));
  EXPECT_LT(worst_axial, 0.01 * (stretch - 1.0) * side);  // within 1% of the elongation
  EXPECT_LT(worst_lateral, 0.01 * (1.0 - lateral) * side);
}

// SOFA's cantilever (0.02 x 0.02 x 0.2 m, E 2e6 Pa, nu 0.45, rho 1100, g 9.81 along -y) solved
// for equilibrium: the mean tip deflection, m.
double static_cantilever_tip(std::array<uint32_t, 3> cells, MaterialLaw law) {
  TestMesh mesh = box_tet_mesh(cells, {0.02, 0.02, 0.2}, 1100.0);
  mesh.fix_plane(2, 0.0);
  Options options;
  options.mode = SolveMode::kStatic;
  options.solver.solver = sparse::LinearSolver::kCholesky;
  auto model = testing::make_model(mesh, law, 2e6, 0.45, true, options);
  Body body(mesh);
  for (uint32_t i = 0; i < mesh.node_count(); ++i) body.f[3 * i + 1] = -9.81 * mesh.masses[i];
  model->begin(body.state, 1.0);
  EXPECT_EQ(model->step(body.state, 1.0) & (TACTA_STEP_FAULT_MASK | TACTA_STEP_SOLVER_NOT_CONVERGED), 0u);
  return -mesh.mean_displacement_on_plane(body.x.data(), 2, 0.2, 1);
}

TEST(HyperelasticValidation, StaticCantileverConvergesUnderRefinement) {
  const double reference = 0.03237 + 0.00038;  // m: Euler-Bernoulli plus Timoshenko shear
  const double coarse = static_cantilever_tip({2, 2, 11}, MaterialLaw::kNeoHookean);
  const double medium = static_cantilever_tip({4, 4, 29}, MaterialLaw::kNeoHookean);
  std::printf("static Neo-Hookean cantilever: 3x3x12 nodes %.5f m (%.1f%%), 5x5x30 %.5f m "
              "(%.1f%%), analytic %.5f m\n",
              coarse, 100 * coarse / reference, medium, 100 * medium / reference, reference);
  // Linear tets lock in bending at nu 0.45: the deflection grows toward the analytic value.
  EXPECT_GT(medium, 1.2 * coarse);
  EXPECT_LT(medium, 1.02 * reference);
  EXPECT_GT(medium, 0.5 * reference);
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
    EXPECT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_INVERTED_ELEMENT, 0u) << testing::law_name(law);
    EXPECT_LT(model->elastic_energy(body.x.data()), 1e-3 * initial_energy) << testing::law_name(law);
  }
}

}  // namespace
}  // namespace tacta::models::hyperelastic
