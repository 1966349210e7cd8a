// The paper's experiment (section 7) as a standalone check: Debunne's model on the 4-node unit
// square, nodes SW (0,0), SE (1,0), NW (0,1), NE (1,1); rho 1, mu 0.01, lambda 1; no gravity,
// nothing fixed. Edge graph: the four sides only. The paper says the displaced NE corner first
// moves its neighbours NW and SE and only then SW, so SW is not a neighbour of NE: no diagonals.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

#include "fd_test_body.hpp"
#include "tacta/models/model_checks.hpp"

using namespace tacta::models;
using namespace tacta::models::testing;

namespace {

struct SquareRun {
  double energy_start = 0, energy_max = 0, energy_end = 0;  // J (per m of thickness)
  double max_displacement = 0;                              // m, over all nodes and steps
  double shape_error_end = 0;   // m: largest |edge length - rest length| at the end
  double com_x = 0, com_y = 0;  // m: centre of mass at the end
  double speed_end = 0;         // m/s: largest node speed at the end
  uint32_t status = 0;
  int fault_step = -1;
};

SquareRun run_square(FdDebunneOptions options, double corner, double dt, int steps,
                     uint32_t cells = 1) {
  FdBody body(quad_grid_mesh(cells, cells, 1.0, 1.0, 1.0), make_material_lame(1.0, 0.01, 1.0),
              options);
  checks::StateBuffers s(body.mesh.positions);
  const size_t ne = 3 * (static_cast<size_t>(cells + 1) * (cells + 1) - 1);  // last node: (1, 1)
  s.x[ne] += corner, s.x[ne + 1] += corner;
  auto energy = [&] {
    double e = body.model->elastic_energy(s.x.data());
    for (size_t i = 0; i < s.v.size(); ++i) e += 0.5 * body.mesh.masses[i / 3] * s.v[i] * s.v[i];
    return e;
  };
  SquareRun r;
  r.energy_start = r.energy_max = energy();
  for (int k = 0; k < steps && r.status == 0; ++k) {
    tacta_body_state st = s.state(k * dt);
    r.status = body.model->step(st, dt);
    if (r.status) r.fault_step = k + 1;
    r.energy_max = std::max(r.energy_max, energy());
    for (size_t i = 0; i < s.x.size(); ++i)
      r.max_displacement = std::max(r.max_displacement, std::abs(s.x[i] - body.mesh.positions[i]));
  }
  r.energy_end = energy();
  for (size_t e = 0; e < body.mesh.edges.size(); e += 2) {
    const size_t a = 3 * body.mesh.edges[e], b = 3 * body.mesh.edges[e + 1];
    const double l = std::hypot(s.x[a] - s.x[b], s.x[a + 1] - s.x[b + 1]);
    const double rest = std::hypot(body.mesh.positions[a] - body.mesh.positions[b],
                                   body.mesh.positions[a + 1] - body.mesh.positions[b + 1]);
    r.shape_error_end = std::max(r.shape_error_end, std::abs(l - rest));
  }
  double total_mass = 0;
  for (uint32_t i = 0; i < body.mesh.node_count(); ++i) {
    const double m = body.mesh.masses[i];
    total_mass += m;
    r.com_x += m * s.x[3 * i], r.com_y += m * s.x[3 * i + 1];
    r.speed_end = std::max(r.speed_end, std::hypot(s.v[3 * i], s.v[3 * i + 1]));
  }
  r.com_x /= total_mass, r.com_y /= total_mass;
  return r;
}

void print(const char* label, const SquareRun& r) {
  std::printf(
      "%s: E0 %.4e J, Emax %.4e, Eend %.4e, max|d| %.4f m, shape err %.2e m, "
      "COM (%.5f, %.5f), max speed %.2e m/s, status %u at step %d\n",
      label, r.energy_start, r.energy_max, r.energy_end, r.max_displacement, r.shape_error_end,
      r.com_x, r.com_y, r.speed_end, r.status, r.fault_step);
}

FdDebunneOptions paper_options(double damping) {
  FdDebunneOptions o;
  o.integrator = FdDebunneOptions::Integrator::kExplicitEuler;
  o.operator_scale = FdDebunneOptions::OperatorScale::kPaper;
  o.damping = damping;
  return o;
}

}  // namespace

TEST(UnitSquareExperiment, CaseAExplicitEulerGainsEnergyEveryPeriod) {
  const SquareRun a = run_square(paper_options(0.0), -0.1, 0.01, 3710);
  print("case A (explicit Euler, dt 0.01, 3710 steps)", a);
  // Forward Euler amplifies every undamped mode by sqrt(1 + (omega dt)^2) per step: the energy
  // grows without bound, but at this dt slowly (see docs/VALIDATION.md for the numbers).
  EXPECT_GT(a.energy_end, 1.05 * a.energy_start);
  EXPECT_EQ(a.status, 0u);
  // The same case with symplectic Euler keeps its energy.
  FdDebunneOptions stable = paper_options(0.0);
  stable.integrator = FdDebunneOptions::Integrator::kSymplecticEuler;
  const SquareRun sym = run_square(stable, -0.1, 0.01, 3710);
  print("case A with symplectic Euler", sym);
  EXPECT_LT(sym.energy_max, 1.05 * sym.energy_start);
  // Run long enough and forward Euler does blow up: the guard reports it.
  const SquareRun longer = run_square(paper_options(0.0), -0.1, 0.01, 400000);
  print("case A continued to 400,000 steps", longer);
  EXPECT_NE(longer.status, 0u);
}

TEST(UnitSquareExperiment, CaseBKeepsShapeAndSettlesShiftedByTheCentreOfMass) {
  const SquareRun b = run_square(paper_options(0.2), -0.05, 0.04, 9472);
  print("case B (explicit Euler, damping 0.2, dt 0.04, 9472 steps)", b);
  EXPECT_EQ(b.status, 0u);
  EXPECT_LT(b.shape_error_end, 1e-6);  // back to a unit square
  EXPECT_LT(b.speed_end, 1e-6);        // at rest
  // On this symmetric 4-node graph every pair force is equal and opposite, so the centre of
  // mass never moves: it starts at (0.5 - 0.05/4, 0.5 - 0.05/4) and the square comes to rest
  // there, i.e. the whole square ends translated by (-0.0125, -0.0125) m.
  EXPECT_NEAR(b.com_x, 0.5 - 0.0125, 1e-9);
  EXPECT_NEAR(b.com_y, 0.5 - 0.0125, 1e-9);
}

TEST(UnitSquareExperiment, RefinedSquareAndStableIntegrator) {
  // The paper's next step: refine the square (8x8 quads, the same NE corner displacement).
  // Explicit Euler's per-step gain sqrt(1 + (omega dt)^2) grows with the highest frequency,
  // which grows as the mesh is refined: case A diverges sooner. Symplectic Euler stays bounded.
  const SquareRun a_fine = run_square(paper_options(0.0), -0.1, 0.01, 3710, 8);
  print("case A on 8x8 quads, explicit Euler", a_fine);
  FdDebunneOptions symplectic = paper_options(0.0);
  symplectic.integrator = FdDebunneOptions::Integrator::kSymplecticEuler;
  const SquareRun a_fine_sym = run_square(symplectic, -0.1, 0.01, 3710, 8);
  print("case A on 8x8 quads, symplectic Euler", a_fine_sym);
  EXPECT_GT(a_fine.energy_max / a_fine.energy_start, 2.0);
  EXPECT_EQ(a_fine_sym.status, 0u);
  EXPECT_LT(a_fine_sym.energy_max, 1.5 * a_fine_sym.energy_start);  // O(omega dt) oscillation
  FdDebunneOptions damped = paper_options(0.2 / 64);  // the same damping per unit mass
  const SquareRun b_fine = run_square(damped, -0.05, 0.04, 9472, 8);
  print("case B on 8x8 quads, explicit Euler, damping 0.2/64 per node", b_fine);
  EXPECT_NE(b_fine.status, 0u);  // dt = 0.04 s is beyond the refined mesh's explicit limit
}
