// Time stepping of the corotational FEM: inversion recovery, damping, fixed nodes, and a step
// that allocates nothing (malloc is interposed in this test binary to count).
#include <cmath>
#include <gtest/gtest.h>

#include "allocation_counter.hpp"  // the shared malloc interposer; off under the sanitizers
#include "corotational_test_support.hpp"

namespace tacta::models::corotational {
namespace {

using testing::BodyState;
using testing::make_model;

double min_volume(const TestMesh& mesh, const std::vector<double>& x) {
  double smallest = 1e300;
  for (size_t t = 0; t < mesh.tets.size(); t += 4)
    smallest = std::min(smallest, tet_signed_volume(node_position(x.data(), mesh.tets[t]),
                                                    node_position(x.data(), mesh.tets[t + 1]),
                                                    node_position(x.data(), mesh.tets[t + 2]),
                                                    node_position(x.data(), mesh.tets[t + 3])));
  return smallest;
}

struct Setting {
  RotationMethod rotation;
  LinearSolver solver;
  Preconditioner preconditioner = Preconditioner::kBlockJacobi;
};

class CorotationalDynamics : public ::testing::TestWithParam<Setting> {
 protected:
  Options options() const {
    Options o;
    o.rotation = GetParam().rotation;
    o.solver = GetParam().solver;
    o.preconditioner = GetParam().preconditioner;
    o.max_iterations = 200;
    o.tolerance = 1e-8;
    return o;
  }
};

TEST_P(CorotationalDynamics, InvertedElementRecovers) {
  // One diagonal: the centre node is in some of the tets. In the symmetric split every cube's
  // diagonal meets at the centre (48 tets around it), and this push trips the divergence guard.
  TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.2, 0.2, 0.2}, 1000.0, GridSplit::kOneDiagonal);
  tacta_material material = make_material(1e5, 0.3, 1000.0);
  material.rayleigh_mass = 5.0;  // 1/s: settle within the test's simulated second
  auto model = make_model(mesh, material, options());
  BodyState body(mesh);
  // Push the centre node (0.1, 0.1, 0.1) out through the +x faces: the tets on that side turn
  // inside out, and the surrounding ones must pull them back.
  const uint32_t centre = 1 + 3 * (1 + 3 * 1);
  body.positions[3 * centre] += 0.15;
  ASSERT_LT(min_volume(mesh, body.positions), 0.0);
  model->begin(body.state, 1e-3);
  uint32_t flags = model->step(body.state, 1e-3);
  EXPECT_NE(flags & TACTA_STEP_INVERTED_ELEMENT, 0u);  // reported while inverted
  for (int i = 0; i < 1000; ++i) flags |= model->step(body.state, 1e-3);
  EXPECT_EQ(flags & TACTA_STEP_FAULT_MASK, 0u);
  const double rest_volume = 0.1 * 0.1 * 0.1 / 6.0;  // m^3, each tet of the 6-tet split
  EXPECT_GT(min_volume(mesh, body.positions), 0.9 * rest_volume);
  EXPECT_LT(model->elastic_energy(body.positions.data()), 1e-6);
}

TEST_P(CorotationalDynamics, DampingDrainsEnergy) {
  TestMesh mesh = box_tet_mesh({2, 2, 4}, {0.1, 0.1, 0.2}, 1000.0);
  tacta_material material = make_material(1e5, 0.3, 1000.0);
  material.rayleigh_mass = 5.0;  // 1/s: also damps the rigid part of the initial motion
  material.rayleigh_stiffness = 0.01;
  auto model = make_model(mesh, material, options());
  BodyState body(mesh);
  for (uint32_t i = 0; i < mesh.node_count(); ++i)  // twist plus stretch
    body.velocities[3 * i] = 2.0 * (mesh.positions[3 * i + 2] - 0.1);
  model->begin(body.state, 1e-3);
  const auto energy = [&] {
    return body.kinetic_energy(mesh) + model->elastic_energy(body.positions.data());
  };
  const double initial = energy();
  double previous = initial;
  for (int i = 0; i < 500; ++i) {
    ASSERT_EQ(model->step(body.state, 1e-3) & TACTA_STEP_FAULT_MASK, 0u);
    const double now = energy();
    EXPECT_LE(now, previous * (1 + 1e-9)) << "step " << i;
    previous = now;
  }
  EXPECT_LT(previous, 0.05 * initial);
}

TEST_P(CorotationalDynamics, FixedNodesStayAndGravityPulls) {
  TestMesh mesh = box_tet_mesh({2, 2, 6}, {0.02, 0.02, 0.2}, 1100.0);
  mesh.fix_plane(2, 0.0);
  auto model = make_model(mesh, make_material(2e6, 0.45, 1100.0), options());
  BodyState body(mesh);
  body.add_gravity(mesh, {0.0, -9.81, 0.0});
  model->begin(body.state, 1e-3);
  for (int i = 0; i < 50; ++i) ASSERT_EQ(model->step(body.state, 1e-3), 0u);
  for (uint32_t i = 0; i < mesh.node_count(); ++i) {
    if (mesh.fixed[i]) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(body.positions[3 * i + c], mesh.positions[3 * i + c]);
    } else if (mesh.positions[3 * i + 2] > 0.19) {
      EXPECT_LT(body.positions[3 * i + 1], mesh.positions[3 * i + 1] - 1e-4);  // tip sags
    }
  }
}

TEST_P(CorotationalDynamics, StepAllocatesNothing) {
  if (!TACTA_COUNT_ALLOCATIONS) GTEST_SKIP() << "a sanitizer owns malloc";
  TestMesh mesh = box_tet_mesh({3, 3, 6}, {0.1, 0.1, 0.2}, 1000.0);
  mesh.fix_plane(2, 0.0);
  tacta_material material = make_material(1e5, 0.4, 1000.0);
  material.rayleigh_mass = 0.1;
  material.rayleigh_stiffness = 0.01;
  auto model = make_model(mesh, material, options());
  BodyState body(mesh);
  body.add_gravity(mesh, {0.0, -9.81, 0.0});
  model->begin(body.state, 1e-3);
  g_allocations = 0;
  g_counting = true;
  uint32_t bits = 0;
  for (int i = 0; i < 20; ++i) bits |= model->step(body.state, 1e-3);
  const long in_steps = g_allocations;
  // The counter works: building a model allocates.
  auto another = make_model(mesh, material, options());
  g_counting = false;
  EXPECT_EQ(bits & TACTA_STEP_FAULT_MASK, 0u);
  EXPECT_EQ(in_steps, 0);
  EXPECT_GT(g_allocations, in_steps);
}

INSTANTIATE_TEST_SUITE_P(
    Methods, CorotationalDynamics,
    ::testing::Values(Setting{RotationMethod::kPolar, LinearSolver::kConjugateGradient},
                      Setting{RotationMethod::kSvd, LinearSolver::kConjugateGradient},
                      Setting{RotationMethod::kPolar, LinearSolver::kCholesky},
                      Setting{RotationMethod::kPolar, LinearSolver::kConjugateGradient,
                              Preconditioner::kIncompleteCholesky}),
    [](const auto& param_info) {
      return std::string(param_info.param.rotation == RotationMethod::kPolar ? "polar" : "svd") +
             (param_info.param.solver == LinearSolver::kCholesky ? "_cholesky" : "_pcg") +
             (param_info.param.preconditioner == Preconditioner::kIncompleteCholesky ? "_ic" : "");
    });

TEST(CorotationalInput, RejectsInvertedRestElement) {
  TestMesh mesh = box_tet_mesh({1, 1, 1}, {0.1, 0.1, 0.1}, 1000.0);
  std::swap(mesh.tets[0], mesh.tets[1]);
  try {
    make_model(mesh, make_material(1e5, 0.3, 1000.0));
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("tet 0"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace tacta::models::corotational
