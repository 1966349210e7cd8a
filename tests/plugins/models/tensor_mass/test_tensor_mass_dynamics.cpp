// tensor_mass: wave speeds, energy drift, stable step, implicit Euler.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <gtest/gtest.h>

#include "tacta/models/lame.hpp"
#include "tacta/models/model_checks.hpp"
#include "tm_test_body.hpp"

using namespace tacta::models;
using namespace tacta::models::testing;

namespace {

// Tip signal of a bar fixed at x = 0 started in the shape `shape` (displacement per node),
// stepped by central differences; returns the period (s) from the tip's zero crossings.
template <class Shape, class Probe>
double bar_period(TmBody& body, Shape&& shape, Probe&& probe, double dt, double duration) {
  checks::StateBuffers s(body.mesh.positions);
  for (uint32_t i = 0; i < body.mesh.node_count(); ++i)
    shape(&body.mesh.positions[3 * i], &s.x[3 * i]);
  tacta_body_state st = s.state();
  body.model->begin(st, dt);
  std::vector<double> signal;
  for (int k = 0; k < static_cast<int>(duration / dt); ++k) {
    st = s.state();
    EXPECT_EQ(body.model->step(st, dt), TACTA_STEP_OK);
    signal.push_back(probe(s.x));
  }
  return checks::period_from_crossings(signal, dt);
}

}  // namespace

TEST(TensorMassWaves, PWaveSpeedFromFirstLongitudinalMode) {
  // nu = 0: no lateral contraction, so the bar's longitudinal speed is the P speed
  // sqrt((lambda + 2 mu) / rho) = sqrt(E / rho) exactly.
  const double length = 1.0, rho = 1000.0;
  TestMesh mesh = box_tet_mesh({20, 2, 2}, {length, 0.1, 0.1}, rho);
  mesh.fix_plane(0, 0.0);
  TmBody body(std::move(mesh), make_material(1e5, 0.0, rho));
  const double cp = p_wave_speed(body.material.lame_lambda, body.material.lame_mu, rho);
  const uint32_t tip = 20;
  const double period = bar_period(
      body,
      [&](const double* rest, double* x) {
        x[0] += 1e-4 * std::sin(M_PI * rest[0] / (2 * length));
      },
      [&](const std::vector<double>& x) { return x[3 * tip] - length; }, 0.1 * 0.05 / cp,
      3.5 * 4 * length / cp);
  const double speed = 4 * length / period;
  std::printf("tensor_mass P: 20x2x2 bar, nu 0: %.4f m/s (exact %.4f, %+.2f%%)\n", speed, cp,
              100 * (speed / cp - 1));
  EXPECT_NEAR(speed / cp, 1.0, 0.05);
}

TEST(TensorMassWaves, SWaveSpeedFromFirstTorsionalMode) {
  // A square bar in torsion: St-Venant's torsion constant J = 0.1406 a^4 against the polar
  // moment a^4/6 (Roark), so the torsional wave travels at c_s sqrt(6 * 0.1406) = 0.9185 c_s.
  const double length = 1.0, rho = 1000.0;
  const double side = std::getenv("TACTA_SIDE") ? std::atof(std::getenv("TACTA_SIDE")) : 0.2;  // m
  const uint32_t across = 8;  // cells across the section
  // Cells along the bar; TACTA_ALONG=80 gives the finer run recorded in docs/VALIDATION.md.
  const char* along_env = std::getenv("TACTA_ALONG");
  const uint32_t along = along_env ? static_cast<uint32_t>(std::atoi(along_env)) : 40u;
  TestMesh mesh = box_tet_mesh({along, across, across}, {length, side, side}, rho);
  mesh.fix_plane(0, 0.0);
  TmBody body(std::move(mesh), make_material(1e5, 0.25, rho));
  const double cs = s_wave_speed(body.material.lame_mu, rho);
  const double c_torsion = cs * std::sqrt(6 * 0.1406);
  auto twist = [&](const double* rest, double* x) {
    const double angle = 1e-3 * std::sin(M_PI * rest[0] / (2 * length));  // rad
    const double y = rest[1] - side / 2, z = rest[2] - side / 2;
    x[1] += -angle * z, x[2] += angle * y;
  };
  // Probe: the tip's rotation, from the corner node (L, side, side) and (L, 0, side).
  const uint32_t nx = along + 1, ny = across + 1;
  const uint32_t corner = along + nx * (across + ny * across);
  const double period = bar_period(
      body, twist, [&](const std::vector<double>& x) { return x[3 * corner + 1] - side; },
      0.4 * std::min(length / along, side / across) /
          p_wave_speed(body.material.lame_lambda, body.material.lame_mu, rho),
      2.1 * 4 * length / c_torsion);  // two upward tip crossings (0.75 T and 1.75 T)
  const double speed = 4 * length / period / std::sqrt(6 * 0.1406);  // back to c_s
  std::printf(
      "tensor_mass S: %ux%ux%u bar (side %.2f m) torsion: c_s %.4f m/s (exact %.4f, %+.2f%%)\n",
      along, across, across, side, speed, cs, 100 * (speed / cs - 1));
  EXPECT_NEAR(speed / cs, 1.0, 0.05);
}

TEST(TensorMassDynamics, CentralDifferenceEnergyBoundedWithoutDamping) {
  TmBody body(box_tet_mesh({3, 3, 3}, {1, 1, 1}, 1000.0), make_material(1e4, 0.3, 1000.0));
  checks::StateBuffers s(body.mesh.positions);
  checks::TestRandom random(3);
  for (double& x : s.x) x += 1e-3 * random.next();
  const double dt = 0.005;  // s, about 0.2 of the measured critical step
  tacta_body_state st = s.state();
  body.model->begin(st, dt);
  auto total = [&] {
    double kinetic = 0;
    for (size_t i = 0; i < s.v.size(); ++i)
      kinetic += 0.5 * body.mesh.masses[i / 3] * s.v[i] * s.v[i];
    return kinetic + body.model->elastic_energy(s.x.data());
  };
  const int steps = 5000;
  double lo = 1e300, hi = 0, early = 0, late = 0;
  for (int k = 0; k < steps; ++k) {
    st = s.state();
    ASSERT_EQ(body.model->step(st, dt), TACTA_STEP_OK);
    const double e = total();  // velocity at t + dt/2 with x at t + dt: oscillates, no trend
    lo = std::min(lo, e), hi = std::max(hi, e);
    if (k < 1000) early += e / 1000;
    if (k >= steps - 1000) late += e / 1000;
  }
  std::printf(
      "tensor_mass central differences, dt %.1e s, %d steps: energy range %.2f%% of mean, mean "
      "drift %+.3f%%\n",
      dt, steps, 100 * (hi - lo) / early, 100 * (late / early - 1));
  EXPECT_LT((hi - lo) / early, 0.3);
  EXPECT_NEAR(late / early, 1.0, 0.01);
}

TEST(TensorMassDynamics, StableStepScalesWithElementSize) {
  const tacta_material material = make_material(1e4, 0.3, 1000.0);
  const double cp = p_wave_speed(material.lame_lambda, material.lame_mu, material.density);
  std::printf(
      "tensor_mass stable dt (unit cube, 6 tets per cell, central differences)\n  cells  h (m)   "
      "dt_crit (s)  dt_crit*c_p/h\n");
  double first = 0;
  for (uint32_t cells : {2u, 4u, 6u}) {
    TmBody body(box_tet_mesh({cells, cells, cells}, {1, 1, 1}, 1000.0), material);
    auto stable = [&](double dt) {
      checks::StateBuffers s(body.mesh.positions);
      checks::TestRandom random(5);
      for (double& v : s.v) v = 1e-6 * random.next();
      tacta_body_state st = s.state();
      body.model->begin(st, dt);
      return checks::stays_bounded(*body.model, s, dt, 1000, 1e-4);
    };
    const double h = 1.0 / cells;
    const double dt = checks::critical_dt(stable, 0.01 * h / cp, 10 * h / cp, 10);
    std::printf("  %5u  %.4f  %.4e   %.3f\n", cells, h, dt, dt * cp / h);
    if (first == 0) first = dt * cp / h;
    EXPECT_NEAR(dt * cp / h, first, 0.25 * first);
  }
}

TEST(TensorMassDynamics, ImplicitEulerStableFarBeyondExplicitLimitAndDamps) {
  const double dt = 0.01;  // s: about 30x the central-difference limit for this mesh (3.3e-4 s)
  TensorMassOptions options;
  options.integrator = TensorMassOptions::Integrator::kImplicitEuler;
  TestMesh mesh = box_tet_mesh({6, 2, 2}, {1, 0.3, 0.3}, 1000.0);
  mesh.fix_plane(0, 0.0);
  TmBody body(std::move(mesh), make_material(1e7, 0.3, 1000.0), options, dt);  // tip sag ~1.6 cm
  checks::StateBuffers s(body.mesh.positions);
  for (size_t i = 2; i < s.f_ext.size(); i += 3) s.f_ext[i] = -9.81 * body.mesh.masses[i / 3];
  for (int k = 0; k < 400; ++k) {
    tacta_body_state st = s.state();
    ASSERT_EQ(body.model->step(st, dt), TACTA_STEP_OK);
  }
  // Settles to the static solution K d = f_ext: internal force balances gravity at free nodes.
  std::vector<double> f(s.x.size());
  body.model->internal_forces(s.x.data(), f.data());
  double residual = 0, load = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    if (body.mesh.fixed[i / 3]) continue;
    residual = std::max(residual, std::abs(f[i] + s.f_ext[i]));
    load = std::max(load, std::abs(s.f_ext[i]));
  }
  EXPECT_LT(residual, 1e-3 * load);
  for (size_t i = 0; i < s.x.size(); ++i)
    if (body.mesh.fixed[i / 3]) {
      EXPECT_EQ(s.x[i], body.mesh.positions[i]);
    }
}
