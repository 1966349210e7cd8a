// Shared helpers for the hyperelastic tests: models built straight from the core library on a
// test mesh, the material of each law from (E, nu), and a dense copy of the block matrix.
#pragma once

#include <Eigen/Core>
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "hyperelastic_model.hpp"
#include "tacta/models/test_meshes.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::hyperelastic::testing {

inline std::vector<MaterialLaw> all_laws() {
  return {MaterialLaw::kNeoHookean, MaterialLaw::kStVenantKirchhoff, MaterialLaw::kMooneyRivlin};
}
inline std::string law_name(MaterialLaw law) {
  return law == MaterialLaw::kNeoHookean          ? "NeoHookean"
         : law == MaterialLaw::kStVenantKirchhoff ? "StVenantKirchhoff"
                                                  : "MooneyRivlin";
}

// Mooney-Rivlin gets C10 = 0.3 mu, C01 = 0.2 mu (small-strain shear modulus mu) and K from nu.
inline MaterialConstants material_for(MaterialLaw law, double youngs_modulus, double poisson) {
  MaterialConstants m;
  m.law = law;
  m.mu = youngs_modulus / (2.0 * (1.0 + poisson));
  m.lambda = youngs_modulus * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  m.c10 = 0.3 * m.mu;
  m.c01 = 0.2 * m.mu;
  m.bulk = m.lambda + 2.0 * m.mu / 3.0;
  return m;
}

inline std::unique_ptr<HyperelasticModel> make_model(const TestMesh& mesh, MaterialLaw law,
                                                     double youngs_modulus, double poisson,
                                                     bool project, Options options = {}) {
  options.material = material_for(law, youngs_modulus, poisson);
  options.project_tangent = project;
  const tacta_material material = make_material(youngs_modulus, poisson, 1000.0);
  return std::make_unique<HyperelasticModel>(mesh.view(), material, mesh.masses, mesh.fixed,
                                             options);
}

inline Eigen::MatrixXd dense(const sparse::BlockSparseMatrix& a) {
  const size_t n = 3 * static_cast<size_t>(a.node_count());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n, n);
  const auto starts = a.row_starts();
  const auto columns = a.columns();
  for (uint32_t i = 0; i < a.node_count(); ++i)
    for (uint32_t k = starts[i]; k < starts[i + 1]; ++k)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          m(3 * i + r, 3 * columns[k] + c) = a.block(k)[3 * r + c];
          m(3 * columns[k] + c, 3 * i + r) = a.block(k)[3 * r + c];
        }
  return m;
}

// A cube's nodes scaled by 1.1 and moved randomly by up to `amount` (m): no inversion.
inline std::vector<double> deformed_cube(const TestMesh& mesh, unsigned seed, double amount) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-amount, amount);
  std::vector<double> x = mesh.positions;
  for (double& c : x) c = 1.1 * c + uniform(random);
  return x;
}

// The largest difference between the forces and -dW/dx by central differences, as a share of
// the largest force.
inline double force_gradient_error(HyperelasticModel& model, std::vector<double> x) {
  std::vector<double> f(x.size());
  model.internal_forces(x.data(), f.data());
  double scale = 0.0, worst = 0.0;
  for (const double v : f) scale = std::max(scale, std::abs(v));
  const double h = 1e-7;
  for (size_t k = 0; k < x.size(); ++k) {
    const double saved = x[k];
    x[k] = saved + h;
    const double up = model.elastic_energy(x.data());
    x[k] = saved - h;
    const double down = model.elastic_energy(x.data());
    x[k] = saved;
    worst = std::max(worst, std::abs(-(up - down) / (2 * h) - f[k]));
  }
  return worst / scale;
}

// The largest difference between the assembled tangent (returned in tangent) and -df/dx by
// central differences, as a share of the tangent's largest entry.
inline double tangent_jacobian_error(HyperelasticModel& model, std::vector<double> x,
                                     Eigen::MatrixXd& tangent) {
  tangent = dense(model.assemble_stiffness(x.data()));
  const size_t n = x.size();
  std::vector<double> up(n), down(n);
  const double h = 1e-7;
  double worst = 0.0;
  for (size_t j = 0; j < n; ++j) {
    const double saved = x[j];
    x[j] = saved + h;
    model.internal_forces(x.data(), up.data());
    x[j] = saved - h;
    model.internal_forces(x.data(), down.data());
    x[j] = saved;
    for (size_t i = 0; i < n; ++i)
      worst = std::max(worst, std::abs(-(up[i] - down[i]) / (2 * h) - tangent(i, j)));
  }
  return worst / tangent.cwiseAbs().maxCoeff();
}

// The rest positions turned by 1.1 rad about (1, 2, 3) and shifted: a rigid motion.
inline std::vector<double> rigidly_moved(const TestMesh& mesh) {
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<double> x = mesh.positions;
  for (size_t i = 0; i < x.size(); i += 3) {
    const Eigen::Vector3d p =
        r * Eigen::Vector3d(x[i], x[i + 1], x[i + 2]) + Eigen::Vector3d(0.3, -1, 2);
    for (int c = 0; c < 3; ++c) x[i + c] = p[c];
  }
  return x;
}

struct InvertedCorner {
  double lowest_eigenvalue_share = 0.0;  // the tangent's lowest eigenvalue / its largest
  bool finite = true;                    // every force component
  double corner_force = 0.0;             // N, along +z on the pushed corner
};
// A 1-cell cube's top corner pushed through to below its base (several tets invert): the
// projected tangent's spectrum and the forces there.
inline InvertedCorner push_corner_through(HyperelasticModel& model, const TestMesh& mesh) {
  std::vector<double> x = mesh.positions, f(x.size());
  const uint32_t top = mesh.node_count() - 1;
  x[3 * top + 2] = -0.05;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(
      dense(model.assemble_stiffness(x.data())));
  InvertedCorner result;
  result.lowest_eigenvalue_share = eigen.eigenvalues().minCoeff() / eigen.eigenvalues().maxCoeff();
  model.internal_forces(x.data(), f.data());
  for (const double v : f) result.finite = result.finite && std::isfinite(v);
  result.corner_force = f[3 * top + 2];
  return result;
}

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
inline std::pair<double, double> neo_hookean_uniaxial(double mu, double lambda, double s) {
  double t = 1.0;
  for (int i = 0; i < 50; ++i) {  // Newton on the lateral equation
    const double log_j = std::log(s * t * t);
    const double g = mu * t + (lambda * log_j - mu) / t;
    const double dg = mu + (2.0 * lambda - lambda * log_j + mu) / (t * t);
    t -= g / dg;
  }
  return {t, mu * s + (lambda * std::log(s * t * t) - mu) / s};
}

struct UniaxialResult {
  double lateral = 0.0, nominal_stress = 0.0;     // analytic lateral stretch; P, Pa
  double worst_axial = 0.0, worst_lateral = 0.0;  // m: largest node error against them
  uint32_t status = 0;
  uint64_t newton_iterations = 0, load_cuts = 0;
};

// A 0.1 m Neo-Hookean cube (E 1e4 Pa, 2x2x4 cells) stretched by `stretch` along z in a static
// solve: the base held at the analytic lateral contraction about the corner (0, 0, 0), the
// analytic nominal stress on the top face as consistent nodal forces (a third of each
// triangle's area per node). Linear tets represent this homogeneous field exactly.
inline UniaxialResult neo_hookean_uniaxial_patch(double nu, double stretch, Volumetric volumetric,
                                                 double static_tolerance = 1e-6) {
  const double side = 0.1, e = 1e4;
  const MaterialConstants m = material_for(MaterialLaw::kNeoHookean, e, nu);
  UniaxialResult result;
  std::tie(result.lateral, result.nominal_stress) = neo_hookean_uniaxial(m.mu, m.lambda, stretch);
  TestMesh mesh = box_tet_mesh({2, 2, 4}, {side, side, side}, 1000.0);
  mesh.fix_plane(2, 0.0);
  Options options;
  options.mode = SolveMode::kStatic;
  options.volumetric = volumetric;
  options.static_tolerance = static_tolerance;
  options.solver.solver = sparse::LinearSolver::kCholesky;
  auto model = make_model(mesh, MaterialLaw::kNeoHookean, e, nu, true, options);
  Body body(mesh);
  for (uint32_t i = 0; i < mesh.node_count(); ++i)
    if (mesh.fixed[i])
      for (int c = 0; c < 2; ++c) body.x[3 * i + c] *= result.lateral;
  for (size_t t = 0; t < mesh.triangles.size(); t += 3) {
    const uint32_t* tri = &mesh.triangles[t];
    bool top = true;
    for (int k = 0; k < 3; ++k) top = top && mesh.positions[3 * tri[k] + 2] > side - 1e-12;
    if (!top) continue;
    const Eigen::Vector3d a = node_position(mesh.positions.data(), tri[0]);
    const Eigen::Vector3d b = node_position(mesh.positions.data(), tri[1]);
    const Eigen::Vector3d c = node_position(mesh.positions.data(), tri[2]);
    const double area = 0.5 * (b - a).cross(c - a).norm();
    for (int k = 0; k < 3; ++k) body.f[3 * tri[k] + 2] += result.nominal_stress * area / 3.0;
  }
  model->begin(body.state, 1.0);
  result.status = model->step(body.state, 1.0);
  for (uint32_t i = 0; i < mesh.node_count(); ++i) {
    result.worst_axial = std::max(
        result.worst_axial, std::abs(body.x[3 * i + 2] - stretch * mesh.positions[3 * i + 2]));
    for (int c = 0; c < 2; ++c)
      result.worst_lateral =
          std::max(result.worst_lateral,
                   std::abs(body.x[3 * i + c] - result.lateral * mesh.positions[3 * i + c]));
  }
  result.newton_iterations = model->counters().newton_iterations;
  result.load_cuts = model->counters().load_cuts;
  return result;
}

// SOFA's cantilever (0.02 x 0.02 x 0.2 m, E 2e6 Pa, rho 1100, g 9.81 along -y) solved for
// equilibrium: the mean tip deflection (m) and the step's status.
inline std::pair<double, uint32_t> static_cantilever_tip(std::array<uint32_t, 3> cells,
                                                         MaterialLaw law, double nu,
                                                         Volumetric volumetric,
                                                         uint64_t* newton_iterations = nullptr,
                                                         GridSplit split = GridSplit::kSymmetric) {
  TestMesh mesh = box_tet_mesh(cells, {0.02, 0.02, 0.2}, 1100.0, split);
  mesh.fix_plane(2, 0.0);
  Options options;
  options.mode = SolveMode::kStatic;
  options.volumetric = volumetric;
  options.solver.solver = sparse::LinearSolver::kCholesky;
  auto model = make_model(mesh, law, 2e6, nu, true, options);
  Body body(mesh);
  for (uint32_t i = 0; i < mesh.node_count(); ++i) body.f[3 * i + 1] = -9.81 * mesh.masses[i];
  model->begin(body.state, 1.0);
  const uint32_t status = model->step(body.state, 1.0);
  if (newton_iterations != nullptr) *newton_iterations = model->counters().newton_iterations;
  return {-mesh.mean_displacement_on_plane(body.x.data(), 2, 0.2, 1), status};
}

}  // namespace tacta::models::hyperelastic::testing
