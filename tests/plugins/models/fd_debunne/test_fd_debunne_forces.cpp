// fd_debunne: static properties of the finite-difference forces.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

#include "fd_test_body.hpp"
#include "tacta/models/model_checks.hpp"

using namespace tacta::models;
using namespace tacta::models::testing;
using checks::TestRandom;

namespace {

// A 2x2x2 box of tets whose interior and surface nodes are jittered: an irregular edge graph.
TestMesh irregular_box() {
  TestMesh m = box_tet_mesh({2, 2, 2}, {1.0, 0.8, 0.6}, 1000.0);
  TestRandom random(7);
  for (double& x : m.positions) x += 0.05 * random.next();
  return m;
}

double norm_of_sum(const std::vector<double>& f) {
  double s[3] = {0, 0, 0};
  for (size_t i = 0; i < f.size(); ++i) s[i % 3] += f[i];
  return std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
}

double sum_of_norms(const std::vector<double>& f) {
  double total = 0;
  for (size_t i = 0; i < f.size(); i += 3)
    total += std::sqrt(f[i] * f[i] + f[i + 1] * f[i + 1] + f[i + 2] * f[i + 2]);
  return total;
}

}  // namespace

class FdDebunneVariants : public ::testing::TestWithParam<bool> {};

TEST_P(FdDebunneVariants, ZeroForceAtRestAndUnderTranslation) {
  FdDebunneOptions options;
  options.symmetric = GetParam();
  FdBody body(irregular_box(), make_material(1e5, 0.3, 1000.0), options);
  std::vector<double> f(body.mesh.positions.size());
  body.model->internal_forces(body.mesh.positions.data(), f.data());
  for (double v : f) EXPECT_EQ(v, 0.0);
  std::vector<double> moved = body.mesh.positions;
  for (size_t i = 0; i < moved.size(); i += 3)
    moved[i] += 0.3, moved[i + 1] -= 1.7, moved[i + 2] += 2.0;
  body.model->internal_forces(moved.data(), f.data());
  for (double v : f) EXPECT_NEAR(v, 0.0, 1e-9);
  EXPECT_NEAR(body.model->elastic_energy(moved.data()), 0.0, 1e-9);  // J, rounding of d
}

INSTANTIATE_TEST_SUITE_P(PaperAndSymmetric, FdDebunneVariants, ::testing::Values(false, true));

TEST(FdDebunne, PaperFormBreaksMomentumOnIrregularMeshSymmetricKeepsIt) {
  std::vector<double> displaced;
  double paper_ratio = 0, symmetric_ratio = 0;
  for (bool symmetric : {false, true}) {
    FdDebunneOptions options;
    options.symmetric = symmetric;
    FdBody body(irregular_box(), make_material(1e5, 0.3, 1000.0), options);
    displaced = body.mesh.positions;
    TestRandom random(11);
    for (double& x : displaced) x += 0.01 * random.next();
    std::vector<double> f(displaced.size());
    body.model->internal_forces(displaced.data(), f.data());
    (symmetric ? symmetric_ratio : paper_ratio) = norm_of_sum(f) / sum_of_norms(f);
  }
  // The paper's per-node normalisation: pair forces differ, the net internal force is not zero.
  EXPECT_GT(paper_ratio, 1e-3);
  EXPECT_LT(symmetric_ratio, 1e-13);
  RecordProperty("paper_net_force_ratio", std::to_string(paper_ratio));
  std::printf("net internal force / sum of |F|: paper %.3e, symmetric %.3e\n", paper_ratio,
              symmetric_ratio);
}

TEST(FdDebunne, SymmetricStiffnessIsSymmetricPositiveSemidefinite) {
  FdDebunneOptions options;
  options.symmetric = true;
  FdBody body(irregular_box(), make_material(1e5, 0.3, 1000.0), options);
  const auto k = checks::stiffness_by_differences(*body.model, body.mesh.positions);
  const auto report = checks::inspect_stiffness(k);
  EXPECT_LT(report.asymmetry, 1e-8);
  EXPECT_GT(report.min_eigenvalue, -1e-8 * report.max_eigenvalue);
  // Paper form: K is not symmetric on an irregular mesh (same cause as the momentum loss).
  FdBody paper(irregular_box(), make_material(1e5, 0.3, 1000.0), FdDebunneOptions{});
  const auto paper_report = checks::inspect_stiffness(
      checks::stiffness_by_differences(*paper.model, paper.mesh.positions));
  EXPECT_GT(paper_report.asymmetry, 1e-3);
}

TEST(FdDebunne, LinearModelIsNotRotationInvariant) {
  // d = x - x_rest: a rigid rotation is a displacement field, so forces appear (stated, not a bug).
  FdDebunneOptions options;
  options.symmetric = true;
  FdBody body(box_tet_mesh({2, 2, 2}, {1, 1, 1}, 1000.0), make_material(1e5, 0.3, 1000.0), options);
  const auto x = checks::rotated_about_z(body.mesh.positions, 0.1);
  std::vector<double> f(x.size());
  body.model->internal_forces(x.data(), f.data());
  EXPECT_GT(sum_of_norms(f), 1.0);
}

TEST(FdDebunne, SurfaceNodesResistAnInfinitesimalRotation) {
  // Why fd_debunne is far too stiff in bending (docs/VALIDATION.md, models that agree): its
  // Laplacian sum_j (d_j - d_i) / ... has no boundary closure, so at a surface node, whose
  // neighbours all lie on one side, a rotation by 1e-6 rad (zero strain: no force in elasticity)
  // loads about as much as a stretch of strain 1e-6. The centre node of the one-diagonal lattice,
  // whose neighbours are point-symmetric with equal weights, feels nothing.
  FdDebunneOptions options;
  options.symmetric = true;
  const double angle = 1e-6;
  FdBody body(box_tet_mesh({4, 4, 4}, {1, 1, 1}, 1000.0, GridSplit::kOneDiagonal),
              make_material(1e5, 0.3, 1000.0), options);
  const auto& rest = body.mesh.positions;
  std::vector<double> rotated(rest.size()), stretched(rest), f_rotation(rest.size()),
      f_stretch(rest.size());
  for (size_t i = 0; i < rest.size(); i += 3) {
    rotated[i] = rest[i] - angle * rest[i + 1];  // d = angle z x x
    rotated[i + 1] = rest[i + 1] + angle * rest[i];
    rotated[i + 2] = rest[i + 2];
    stretched[i] = rest[i] * (1 + angle);  // uniaxial strain 1e-6 along x
  }
  body.model->internal_forces(rotated.data(), f_rotation.data());
  body.model->internal_forces(stretched.data(), f_stretch.data());
  double surface_rotation = 0, surface_stretch = 0;
  for (size_t i = 0; i < rest.size(); i += 3) {
    const double r = std::hypot(f_rotation[i], f_rotation[i + 1], f_rotation[i + 2]);
    const double s = std::hypot(f_stretch[i], f_stretch[i + 1], f_stretch[i + 2]);
    bool surface = false;
    for (int c = 0; c < 3; ++c) surface |= rest[i + c] < 1e-9 || rest[i + c] > 1 - 1e-9;
    if (surface)
      surface_rotation = std::max(surface_rotation, r),
      surface_stretch = std::max(surface_stretch, s);
  }
  const size_t centre = 3 * (2 + 5 * (2 + 5 * 2));  // node (2, 2, 2) of the 5x5x5
  const double interior_rotation =
      std::hypot(f_rotation[centre], f_rotation[centre + 1], f_rotation[centre + 2]);
  std::printf(
      "fd_debunne, 1e-6 rad rotation: largest surface force %.3g N (stretch 1e-6: %.3g N), "
      "centre node %.3g N\n",
      surface_rotation, surface_stretch, interior_rotation);
  EXPECT_GT(surface_rotation, 0.3 * surface_stretch);
  EXPECT_LT(interior_rotation, 1e-6 * surface_rotation);
}
