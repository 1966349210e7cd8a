// Lamé <-> engineering constants, both ways, against hand-computed values.
#include <gtest/gtest.h>

#include "fake_schemas.hpp"

namespace tacta::testing {
namespace {

TEST(SceneMaterials, LameFromYoungsAndPoisson) {
  // E = 1e4 Pa, nu = 0.25: lambda = 1e4 * 0.25 / (1.25 * 0.5) = 4000, mu = 1e4 / 2.5 = 4000.
  const LameParameters l = lame_from_engineering(1e4, 0.25);
  EXPECT_DOUBLE_EQ(l.lambda, 4000);
  EXPECT_DOUBLE_EQ(l.mu, 4000);
  const SceneDesc s = load(yaml(kMinimalScene), {"bodies.0.material.poisson_ratio=0.25"});
  EXPECT_DOUBLE_EQ(s.bodies[0].material.lame_lambda, 4000);
  EXPECT_DOUBLE_EQ(s.bodies[0].material.lame_mu, 4000);
}

TEST(SceneMaterials, YoungsAndPoissonFromLame) {
  // lambda = mu = 1 Pa: E = 1 * 5 / 2 = 2.5, nu = 1 / 4.
  const EngineeringConstants c = engineering_from_lame(1.0, 1.0);
  EXPECT_DOUBLE_EQ(c.youngs_modulus, 2.5);
  EXPECT_DOUBLE_EQ(c.poisson_ratio, 0.25);
  const SceneDesc s =
      load(yaml(kMinimalScene), {"bodies.0.material={lame_lambda: 1, lame_mu: 1, density: 2}"});
  EXPECT_DOUBLE_EQ(s.bodies[0].material.youngs_modulus, 2.5);
  EXPECT_DOUBLE_EQ(s.bodies[0].material.poisson_ratio, 0.25);
  EXPECT_DOUBLE_EQ(s.bodies[0].material.density, 2);
}

TEST(SceneMaterials, RoundTripAcrossTheRange) {
  for (double nu : {-0.9, -0.3, 0.0, 0.2, 0.45, 0.499}) {
    const LameParameters l = lame_from_engineering(3.3e5, nu);
    const EngineeringConstants c = engineering_from_lame(l.lambda, l.mu);
    EXPECT_NEAR(c.youngs_modulus, 3.3e5, 3.3e5 * 1e-12) << nu;
    EXPECT_NEAR(c.poisson_ratio, nu, 1e-12);
  }
}

TEST(SceneMaterials, AuxeticLameAccepted) {
  // lambda = -0.5 mu > -2 mu / 3 (positive bulk modulus): nu = -1 / (2 * 1) = -0.5,
  // E = 2 * (-3 + 4) / (-1 + 2) = 2.
  const SceneDesc s =
      load(yaml(kMinimalScene), {"bodies.0.material={lame_lambda: -1, lame_mu: 2}"});
  EXPECT_DOUBLE_EQ(s.bodies[0].material.poisson_ratio, -0.5);
  EXPECT_DOUBLE_EQ(s.bodies[0].material.youngs_modulus, 2.0);
}

}  // namespace
}  // namespace tacta::testing
