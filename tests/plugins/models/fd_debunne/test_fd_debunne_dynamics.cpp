// fd_debunne: wave speeds, energy drift and the stable step.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <gtest/gtest.h>

#include "fd_test_body.hpp"
#include "tacta/models/lame.hpp"
#include "tacta/models/model_checks.hpp"

using namespace tacta::models;
using namespace tacta::models::testing;

namespace {

constexpr double kLambda = 2.0, kMu = 1.0, kRho = 1.0;  // Pa, Pa, kg/m^3: c_p = 2, c_s = 1 m/s

// First longitudinal (axis 0) or transverse (axis 1) mode of a bar fixed at x = 0, free at
// x = L, on the Cartesian edge graph: period from the tip's zero crossings, speed 4 L / T.
double bar_mode_speed(int axis, FdDebunneOptions::OperatorScale scale, uint32_t cells_across,
                      bool tet_edges = false) {
  const double length = 1.0;
  // TACTA_FINE=1: the finer run recorded in docs/VALIDATION.md (40 cells along, 12 across).
  const bool fine = std::getenv("TACTA_FINE") != nullptr;
  const uint32_t nx = fine ? 40u : 20u;
  if (fine) cells_across = 12;
  const double width = length / nx * cells_across;
  TestMesh mesh =
      tet_edges ? box_tet_mesh({nx, cells_across, cells_across}, {length, width, width}, kRho)
                : grid_edge_mesh({nx, cells_across, cells_across}, {length, width, width}, kRho);
  mesh.fix_plane(0, 0.0);
  FdDebunneOptions options;
  options.operator_scale = scale;
  FdBody body(std::move(mesh), make_material_lame(kLambda, kMu, kRho), options);
  checks::StateBuffers s(body.mesh.positions);
  for (size_t i = 0; i < s.x.size(); i += 3)
    s.x[i + static_cast<size_t>(axis)] +=
        1e-3 * std::sin(M_PI * body.mesh.positions[i] / (2 * length));
  const double c_guess = axis == 0 ? p_wave_speed(kLambda, kMu, kRho) : s_wave_speed(kMu, kRho);
  const double dt = 0.1 * (length / nx) / p_wave_speed(kLambda, kMu, kRho);
  const uint32_t tip = nx;  // node (L, 0, 0)
  std::vector<double> tip_signal;
  const int steps = static_cast<int>(3.5 * 4 * length / c_guess / dt);
  for (int k = 0; k < steps; ++k) {
    tacta_body_state st = s.state();
    EXPECT_EQ(body.model->step(st, dt), TACTA_STEP_OK);
    tip_signal.push_back(s.x[3 * tip + static_cast<size_t>(axis)] -
                         body.mesh.positions[3 * tip + static_cast<size_t>(axis)]);
  }
  const double period = checks::period_from_crossings(tip_signal, dt);
  return period > 0 ? 4 * length / period : 0.0;
}

}  // namespace

TEST(FdDebunneWaves, DimensionScaleGivesPAndSSpeedsWithinFivePercent) {
  const double cp = p_wave_speed(kLambda, kMu, kRho), cs = s_wave_speed(kMu, kRho);
  const double p = bar_mode_speed(0, FdDebunneOptions::OperatorScale::kDimension, 6);
  const double s = bar_mode_speed(1, FdDebunneOptions::OperatorScale::kDimension, 6);
  std::printf(
      "fd_debunne grid bar, scale=dimension: P %.4f (exact %.4f, %+.2f%%), S %.4f (exact %.4f, "
      "%+.2f%%)\n",
      p, cp, 100 * (p / cp - 1), s, cs, 100 * (s / cs - 1));
  EXPECT_NEAR(p / cp, 1.0, 0.05);
  EXPECT_NEAR(s / cs, 1.0, 0.05);
}

TEST(FdDebunneWaves, PaperScaleIsSlowByRootOfDimension) {
  const double cp = p_wave_speed(kLambda, kMu, kRho);
  const double p = bar_mode_speed(0, FdDebunneOptions::OperatorScale::kPaper, 6);
  std::printf("fd_debunne grid bar, scale=paper: P %.4f = %.3f x exact (1/sqrt(3) = 0.577)\n", p,
              p / cp);
  EXPECT_LT(p / cp, 0.7);
  EXPECT_GT(p / cp, 0.5);
}

TEST(FdDebunneWaves, TetEdgeGraphIsAnisotropicNoScaleFitsBoth) {
  // On the 6-tet lattice's edge graph (axis, face- and body-diagonal edges) eq. 17 is not a
  // consistent grad(div): the P/S speed ratio comes out wrong, so no single factor can fix both.
  const double cp = p_wave_speed(kLambda, kMu, kRho), cs = s_wave_speed(kMu, kRho);
  const double p = bar_mode_speed(0, FdDebunneOptions::OperatorScale::kDimension, 6, true);
  const double s = bar_mode_speed(1, FdDebunneOptions::OperatorScale::kDimension, 6, true);
  std::printf("fd_debunne 20x6x6 tet edge graph, scale=dimension: P %.3f x exact, S %.3f x exact\n",
              p / cp, s / cs);
  EXPECT_GT(std::abs(p / cp - s / cs), 0.05);
}

TEST(FdDebunneDynamics, SymplecticEnergyDriftIsBoundedWithoutDamping) {
  FdDebunneOptions options;
  options.symmetric = true;  // the symmetric variant has an exact potential energy
  FdBody body(box_tet_mesh({3, 3, 3}, {1, 1, 1}, 1000.0), make_material(1e4, 0.3, 1000.0), options);
  checks::StateBuffers s(body.mesh.positions);
  checks::TestRandom random(3);
  for (double& v : s.v) v = 1e-3 * random.next();
  const double dt = 0.01;  // s: about 0.13 of the measured critical step (0.861 h / c_p, h = 1/3 m)
  auto total = [&] {
    double kinetic = 0;
    for (size_t i = 0; i < s.v.size(); ++i)
      kinetic += 0.5 * body.mesh.masses[i / 3] * s.v[i] * s.v[i];
    return kinetic + body.model->elastic_energy(s.x.data());
  };
  const double e0 = total();
  double lo = e0, hi = e0, early = 0, late = 0;
  const int steps = 5000;
  for (int k = 0; k < steps; ++k) {
    tacta_body_state st = s.state();
    ASSERT_EQ(body.model->step(st, dt), TACTA_STEP_OK);
    const double e = total();
    lo = std::min(lo, e), hi = std::max(hi, e);
    if (k < 1000) early += e / 1000;
    if (k >= steps - 1000) late += e / 1000;
  }
  // Symplectic Euler's energy oscillates (O(omega dt)) around a conserved shadow energy: the
  // oscillation is bounded and the mean does not drift.
  std::printf(
      "fd_debunne symplectic, dt %.1e s, %d steps: energy range %.2f%% of E0, mean drift %+.3f%%\n",
      dt, steps, 100 * (hi - lo) / e0, 100 * (late / early - 1));
  EXPECT_LT((hi - lo) / e0, 0.15);
  EXPECT_NEAR(late / early, 1.0, 0.01);
}

TEST(FdDebunneDynamics, StableStepScalesWithElementSize) {
  const tacta_material material = make_material(1e4, 0.3, 1000.0);
  const double cp = p_wave_speed(material.lame_lambda, material.lame_mu, material.density);
  std::printf(
      "fd_debunne stable dt (unit cube of tets, symplectic Euler)\n  cells  h (m)   dt_crit (s)  "
      "dt_crit*c_p/h\n");
  double first_ratio = 0;
  for (uint32_t cells : {2u, 4u, 6u}) {
    FdDebunneOptions options;
    options.symmetric = true;
    FdBody body(box_tet_mesh({cells, cells, cells}, {1, 1, 1}, 1000.0), material, options);
    auto stable = [&](double dt) {
      checks::StateBuffers s(body.mesh.positions);
      checks::TestRandom random(5);
      for (double& v : s.v) v = 1e-6 * random.next();
      return checks::stays_bounded(*body.model, s, dt, 1000, 1e-4);
    };
    const double h = 1.0 / cells;
    const double dt = checks::critical_dt(stable, 0.01 * h / cp, 10 * h / cp, 10);
    std::printf("  %5u  %.4f  %.4e   %.3f\n", cells, h, dt, dt * cp / h);
    if (first_ratio == 0) first_ratio = dt * cp / h;
    EXPECT_NEAR(dt * cp / h, first_ratio, 0.25 * first_ratio);  // dt_crit proportional to h
  }
}
