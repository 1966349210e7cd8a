// Consistency of the hyperelastic model's derivatives, each against central finite differences:
// the stretch-space gradient and Hessian of every material, the nodal forces against the
// energy, and the assembled tangent against the forces (exact tangent, non-inverted state).
// Then what makes it robust: no force at rest or under a rigid rotation, and a projected
// tangent that stays positive semi-definite with an element turned inside out.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "hyperelastic_test_support.hpp"
#include "isotropic_element.hpp"

namespace tacta::models::hyperelastic {
namespace {

using testing::all_laws;
using testing::make_model;
using testing::material_for;

class PerLaw : public ::testing::TestWithParam<MaterialLaw> {};

TEST_P(PerLaw, StretchDerivativesMatchFiniteDifferences) {
  const MaterialConstants m = material_for(GetParam(), 1e4, 0.4);
  const Eigen::Vector3d sigma(1.3, 0.85, 0.95);
  const StretchDerivatives d = stretch_derivatives(m, sigma);
  const double h = 1e-6;
  for (int i = 0; i < 3; ++i) {
    Eigen::Vector3d up = sigma, down = sigma;
    up[i] += h;
    down[i] -= h;
    const StretchDerivatives du = stretch_derivatives(m, up), dd = stretch_derivatives(m, down);
    EXPECT_NEAR((du.energy - dd.energy) / (2 * h), d.gradient[i], 1e-6 * 1e4) << i;
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR((du.gradient[k] - dd.gradient[k]) / (2 * h), d.hessian(k, i), 1e-5 * 1e4)
          << i << k;
  }
}

// A 2x2x2-cell cube with every node moved randomly by up to 15% of a cell (no inversion).
std::vector<double> deformed_cube(const TestMesh& mesh, unsigned seed, double amount) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-amount, amount);
  std::vector<double> x = mesh.positions;
  for (double& c : x) c = 1.1 * c + uniform(random);
  return x;
}

TEST_P(PerLaw, ForcesAreMinusTheEnergyGradient) {
  const TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  auto model = make_model(mesh, GetParam(), 1e4, 0.4, /*project=*/false);
  std::vector<double> x = deformed_cube(mesh, 3, 0.007), f(x.size());
  model->internal_forces(x.data(), f.data());
  const double h = 1e-7;
  double scale = 0.0;
  for (const double v : f) scale = std::max(scale, std::abs(v));
  for (size_t k = 0; k < x.size(); ++k) {
    const double saved = x[k];
    x[k] = saved + h;
    const double up = model->elastic_energy(x.data());
    x[k] = saved - h;
    const double down = model->elastic_energy(x.data());
    x[k] = saved;
    EXPECT_NEAR(-(up - down) / (2 * h), f[k], 1e-5 * scale) << k;
  }
}

TEST_P(PerLaw, TangentIsMinusTheForceJacobian) {
  const TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  auto model = make_model(mesh, GetParam(), 1e4, 0.4, /*project=*/false);
  std::vector<double> x = deformed_cube(mesh, 5, 0.007);
  const Eigen::MatrixXd k = testing::dense(model->assemble_stiffness(x.data()));
  const size_t n = x.size();
  std::vector<double> up(n), down(n);
  const double h = 1e-7;
  const double scale = k.cwiseAbs().maxCoeff();
  double worst = 0.0;
  for (size_t j = 0; j < n; ++j) {
    const double saved = x[j];
    x[j] = saved + h;
    model->internal_forces(x.data(), up.data());
    x[j] = saved - h;
    model->internal_forces(x.data(), down.data());
    x[j] = saved;
    for (size_t i = 0; i < n; ++i)
      worst = std::max(worst, std::abs(-(up[i] - down[i]) / (2 * h) - k(i, j)));
  }
  EXPECT_LT(worst, 1e-5 * scale);
}

TEST_P(PerLaw, NoForceAtRestOrUnderRigidRotation) {
  const TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  auto model = make_model(mesh, GetParam(), 1e4, 0.45, true);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(1.1, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<double> x = mesh.positions, f(x.size());
  for (size_t i = 0; i < x.size(); i += 3) {
    const Eigen::Vector3d p = r * Eigen::Vector3d(x[i], x[i + 1], x[i + 2]) + Eigen::Vector3d(0.3, -1, 2);
    for (int c = 0; c < 3; ++c) x[i + c] = p[c];
  }
  for (const auto* positions : {mesh.positions.data(), static_cast<const double*>(x.data())}) {
    model->internal_forces(positions, f.data());
    for (const double v : f) EXPECT_NEAR(v, 0.0, 1e-9);
    EXPECT_NEAR(model->elastic_energy(positions), 0.0, 1e-12);
  }
}

TEST_P(PerLaw, ProjectedTangentStaysPositiveThroughInversion) {
  const TestMesh mesh = box_tet_mesh({1, 1, 1}, {0.1, 0.1, 0.1}, 1000.0);
  auto model = make_model(mesh, GetParam(), 1e4, 0.45, true);
  std::vector<double> x = mesh.positions;
  // The top corner pushed through the cube to below its bottom: several tets invert.
  const uint32_t top = mesh.node_count() - 1;
  x[3 * top + 2] = -0.05;
  const Eigen::MatrixXd k = testing::dense(model->assemble_stiffness(x.data()));
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(k);
  EXPECT_GT(eigen.eigenvalues().minCoeff(), -1e-9 * eigen.eigenvalues().maxCoeff());
  std::vector<double> f(x.size());
  model->internal_forces(x.data(), f.data());
  for (const double v : f) EXPECT_TRUE(std::isfinite(v));
  EXPECT_GT(f[3 * top + 2], 0.0);  // the force pushes the corner back up
}

INSTANTIATE_TEST_SUITE_P(Laws, PerLaw, ::testing::ValuesIn(all_laws()),
                         [](const auto& law) { return testing::law_name(law.param); });

}  // namespace
}  // namespace tacta::models::hyperelastic
