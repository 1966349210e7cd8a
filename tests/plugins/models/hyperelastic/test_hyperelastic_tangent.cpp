// Consistency of the hyperelastic model's derivatives, each against central finite differences:
// the stretch-space gradient and Hessian of every material, the nodal forces against the
// energy, and the assembled tangent against the forces (exact tangent, non-inverted state).
// Then what makes it robust: no force at rest or under a rigid rotation, and a projected
// tangent that stays positive semi-definite with an element turned inside out.
#include <Eigen/Dense>
#include <cmath>
#include <gtest/gtest.h>
#include <random>

#include "hyperelastic_test_support.hpp"
#include "invariant_stress.hpp"
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

// A 2x2x2-cell cube with every node moved randomly by up to 7% of a cell (no inversion).
TEST_P(PerLaw, ForcesAreMinusTheEnergyGradient) {
  const TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  auto model = make_model(mesh, GetParam(), 1e4, 0.4, /*project=*/false);
  EXPECT_LT(testing::force_gradient_error(*model, testing::deformed_cube(mesh, 3, 0.007)), 1e-5);
}

TEST_P(PerLaw, TangentIsMinusTheForceJacobian) {
  const TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  auto model = make_model(mesh, GetParam(), 1e4, 0.4, /*project=*/false);
  Eigen::MatrixXd k;
  EXPECT_LT(testing::tangent_jacobian_error(*model, testing::deformed_cube(mesh, 5, 0.007), k),
            1e-5);
}

TEST_P(PerLaw, NoForceAtRestOrUnderRigidRotation) {
  const TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.1, 0.1, 0.1}, 1000.0);
  auto model = make_model(mesh, GetParam(), 1e4, 0.45, true);
  const std::vector<double> x = testing::rigidly_moved(mesh);
  std::vector<double> f(x.size());
  for (const auto* positions : {mesh.positions.data(), x.data()}) {
    model->internal_forces(positions, f.data());
    for (const double v : f) EXPECT_NEAR(v, 0.0, 1e-9);
    EXPECT_NEAR(model->elastic_energy(positions), 0.0, 1e-12);
  }
}

TEST_P(PerLaw, ProjectedTangentStaysPositiveThroughInversion) {
  const TestMesh mesh = box_tet_mesh({1, 1, 1}, {0.1, 0.1, 0.1}, 1000.0);
  auto model = make_model(mesh, GetParam(), 1e4, 0.45, true);
  const testing::InvertedCorner r = testing::push_corner_through(*model, mesh);
  EXPECT_GT(r.lowest_eigenvalue_share, -1e-9);
  EXPECT_TRUE(r.finite);
  EXPECT_GT(r.corner_force, 0.0);  // the force pushes the corner back up
}

// The SVD-free stress of force-only passes against the stretch-space one, on random F up to
// 30% strain; and the cases it must hand back to the SVD path.
TEST_P(PerLaw, InvariantStressMatchesTheStretchPath) {
  const MaterialConstants m = material_for(GetParam(), 1e4, 0.45);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> strain(-0.3, 0.3);
  int compared = 0;
  for (int sample = 0; sample < 50; ++sample) {
    Eigen::Matrix3d f = Eigen::Matrix3d::Identity();
    for (int k = 0; k < 9; ++k) f(k / 3, k % 3) += strain(random);
    double energy = 0.0;
    Eigen::Matrix3d stress;
    const bool taken = invariant_stress(m, f, energy, &stress);
    if (GetParam() == MaterialLaw::kStVenantKirchhoff) {
      EXPECT_FALSE(taken);
      continue;
    }
    if (!taken) continue;  // the bound could not rule the clamp out: the SVD path's case
    const StretchFrame frame = rotation_variant_svd(f);
    const StretchDerivatives psi = clamped_stretch_derivatives(m, frame.sigma);
    ++compared;
    EXPECT_NEAR(energy, psi.energy, 1e-10 * 1e4) << sample;
    EXPECT_LT((stress - first_piola(frame, psi)).norm(), 1e-9 * 1e4) << sample;
  }
  if (GetParam() != MaterialLaw::kStVenantKirchhoff) {
    EXPECT_GT(compared, 40);
  }
  double energy = 0.0;
  EXPECT_FALSE(invariant_stress(m, Eigen::Vector3d(1.0, 1.0, 0.05).asDiagonal().toDenseMatrix(),
                                energy, nullptr));  // a stretch below min_stretch
  EXPECT_FALSE(invariant_stress(m, Eigen::Vector3d(1.0, 1.0, -0.5).asDiagonal().toDenseMatrix(),
                                energy, nullptr));  // inverted
}

INSTANTIATE_TEST_SUITE_P(Laws, PerLaw, ::testing::ValuesIn(all_laws()),
                         [](const auto& law) { return testing::law_name(law.param); });

}  // namespace
}  // namespace tacta::models::hyperelastic
