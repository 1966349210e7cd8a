// mass_spring: static properties of the spring forces and the stiffness rule.
#include <gtest/gtest.h>

#include <cmath>

#include "ms_test_body.hpp"
#include "tacta/models/model_checks.hpp"

using namespace tacta::models;
using namespace tacta::models::testing;
using checks::TestRandom;

namespace {

double max_abs(const std::vector<double>& f) {
  double r = 0;
  for (double v : f) r = std::max(r, std::abs(v));
  return r;
}

}  // namespace

TEST(MassSpring, ZeroForceAtRestTranslationAndRotationNetForceZero) {
  MsBody body(box_tet_mesh({3, 2, 2}, {0.3, 0.2, 0.2}, 1000.0), make_material(1e5, 0.3, 1000.0));
  std::vector<double> f(body.mesh.positions.size());
  body.model->internal_forces(body.mesh.positions.data(), f.data());
  EXPECT_EQ(max_abs(f), 0.0);
  std::vector<double> x = body.mesh.positions;
  for (size_t i = 0; i < x.size(); i += 3) x[i] += 2.0, x[i + 2] -= 1.0;
  body.model->internal_forces(x.data(), f.data());
  EXPECT_LT(max_abs(f), 1e-8);
  for (double angle : {0.1, 1.0, 3.0}) {  // exact for any angle: springs see only lengths
    const auto r = checks::rotated_about_z(body.mesh.positions, angle);
    body.model->internal_forces(r.data(), f.data());
    EXPECT_LT(max_abs(f), 1e-8) << angle;
    EXPECT_LT(body.model->elastic_energy(r.data()), 1e-15);
  }
  TestRandom random(2);
  for (double& v : x) v += 0.01 * random.next();
  body.model->internal_forces(x.data(), f.data());
  double sum[3] = {0, 0, 0};
  for (size_t i = 0; i < f.size(); ++i) sum[i % 3] += f[i];
  EXPECT_LT(std::abs(sum[0]) + std::abs(sum[1]) + std::abs(sum[2]), 1e-10 * max_abs(f));
}

TEST(MassSpring, StiffnessSymmetricPositiveSemidefiniteAtRest) {
  MsBody body(box_tet_mesh({2, 2, 2}, {0.2, 0.2, 0.2}, 1000.0), make_material(1e5, 0.3, 1000.0));
  const auto report =
      checks::inspect_stiffness(checks::stiffness_by_differences(*body.model, body.mesh.positions, 1e-7));
  EXPECT_LT(report.asymmetry, 1e-6);
  EXPECT_GT(report.min_eigenvalue, -1e-6 * report.max_eigenvalue);
}

TEST(MassSpring, VanGelderStiffnessOnTheCubeLattice) {
  // Interior axis edge of the 6-tet lattice: 6 tets of h^3/6 each -> k = E h.
  const double e_modulus = 1e5, h = 0.1;
  MsBody body(box_tet_mesh({2, 2, 2}, {2 * h, 2 * h, 2 * h}, 1000.0, GridSplit::kOneDiagonal),
              make_material(e_modulus, 0.3, 1000.0));
  const auto& springs = body.model->springs();
  // The edge from the centre node (1,1,1) = 13 to (2,1,1) = 14.
  bool found = false;
  for (size_t s = 0; s < springs.size(); ++s)
    if (springs.ends[2 * s] == 13 && springs.ends[2 * s + 1] == 14) {
      EXPECT_NEAR(springs.stiffness[s], e_modulus * h, 1e-9 * e_modulus * h);
      found = true;
    }
  EXPECT_TRUE(found);
}
