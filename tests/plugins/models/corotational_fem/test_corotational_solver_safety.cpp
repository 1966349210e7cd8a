// Solver safety: with its default settings the corotational FEM must follow the direct solve on
// SOFA's cantilever setup (shared/data/README.md), where a CG capped at 25 iterations and
// accepted unconverged collapsed the beam at 0.44 s.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

#include "corotational_test_support.hpp"

namespace tacta::models::corotational {
namespace {

using testing::BodyState;
using testing::make_model;

struct CantileverRun {
  double tip_deflection = 0.0;  // m, mean -y displacement of the free end after the run
  bool faulted = false;
  SolverCounters counters;
};

// Beam 0.02 x 0.02 x 0.2 m, 5x5x30 nodes, E 2e6 Pa, nu 0.45, rho 1100, Rayleigh 0.1 / 0.1,
// g 9.81 along -y, z = 0 clamped, backward Euler dt 0.01 s, 100 steps.
CantileverRun run_sofa_cantilever(const Options& options) {
  TestMesh mesh = box_tet_mesh({4, 4, 29}, {0.02, 0.02, 0.2}, 1100.0);
  mesh.fix_plane(2, 0.0);
  tacta_material material = make_material(2e6, 0.45, 1100.0);
  material.rayleigh_mass = 0.1;
  material.rayleigh_stiffness = 0.1;
  auto model = make_model(mesh, material, options);
  BodyState body(mesh);
  body.add_gravity(mesh, {0.0, -9.81, 0.0});
  const double dt = 0.01;
  model->begin(body.state, dt);
  CantileverRun run;
  for (int step = 0; step < 100 && !run.faulted; ++step)
    run.faulted = (model->step(body.state, dt) & TACTA_STEP_FAULT_MASK) != 0;
  run.tip_deflection = -mesh.mean_displacement_on_plane(body.positions.data(), 2, 0.2, 1);
  run.counters = model->counters();
  return run;
}

TEST(CorotationalSolverSafety, DefaultFollowsTheDirectSolveOnSofasCantilever) {
  Options direct;
  direct.solver = LinearSolver::kCholesky;
  const CantileverRun reference = run_sofa_cantilever(direct);
  const CantileverRun safe = run_sofa_cantilever(Options{});
  std::printf(
      "cantilever tip after 1 s: direct %.6f m, default %.6f m (%+.4f%%); solves %llu, "
      "CG iterations %llu, warm starts rejected %llu, restarts %llu, direct fallbacks "
      "%llu, held on direct %llu\n",
      reference.tip_deflection, safe.tip_deflection,
      100.0 * (safe.tip_deflection / reference.tip_deflection - 1.0),
      static_cast<unsigned long long>(safe.counters.solves),
      static_cast<unsigned long long>(safe.counters.cg_iterations),
      static_cast<unsigned long long>(safe.counters.warm_starts_rejected),
      static_cast<unsigned long long>(safe.counters.restarts),
      static_cast<unsigned long long>(safe.counters.direct_fallbacks),
      static_cast<unsigned long long>(safe.counters.direct_solves_held));
  ASSERT_FALSE(reference.faulted);
  ASSERT_FALSE(safe.faulted);
  EXPECT_NEAR(safe.tip_deflection / reference.tip_deflection, 1.0, 0.005);
  EXPECT_EQ(safe.counters.unconverged, 0u);
  EXPECT_EQ(safe.counters.solves, 100u);
}

TEST(CorotationalSolverSafety, WithoutFallbackTheCappedSolveDoesNotFollow) {
  // The old default, kept reachable (fallback: none): what the fallbacks are there to prevent.
  Options capped;
  capped.fallback = SolverFallback::kNone;
  Options direct;
  direct.solver = LinearSolver::kCholesky;
  const CantileverRun reference = run_sofa_cantilever(direct);
  const CantileverRun run = run_sofa_cantilever(capped);
  std::printf("capped CG without fallback: %s, tip %.6f m, unconverged solves %llu\n",
              run.faulted ? "faulted" : "ran", run.tip_deflection,
              static_cast<unsigned long long>(run.counters.unconverged));
  EXPECT_GT(run.counters.unconverged, 0u);
  EXPECT_TRUE(run.faulted || std::abs(run.tip_deflection / reference.tip_deflection - 1.0) > 0.005);
}

}  // namespace
}  // namespace tacta::models::corotational
