// mass_spring: static properties of the spring forces and the stiffness rule.
#include <cmath>
#include <gtest/gtest.h>
#include <stdexcept>
#include <string>

#include "ms_test_body.hpp"
#include "tacta/models/model_checks.hpp"
#include "tacta/models/tet_geometry.hpp"

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
  const auto report = checks::inspect_stiffness(
      checks::stiffness_by_differences(*body.model, body.mesh.positions, 1e-7));
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

namespace {

// One regular tet of edge `edge` m, as a mesh: positions, tet, edges, unit masses.
TestMesh regular_tet(double edge) {
  TestMesh mesh;
  const double s = edge / std::sqrt(8.0);  // cube corners (s,s,s), (s,-s,-s), ...: edge 2 s sqrt 2
  mesh.positions = {s, s, s, s, -s, -s, -s, s, -s, -s, -s, s};
  mesh.tets = {0, 1, 2, 3};
  if (tet_signed_volume(
          node_position(mesh.positions.data(), 0), node_position(mesh.positions.data(), 1),
          node_position(mesh.positions.data(), 2), node_position(mesh.positions.data(), 3)) < 0)
    mesh.tets = {0, 2, 1, 3};
  mesh.edges = edges_of_tets(mesh.tets);
  mesh.triangles = boundary_of_tets(mesh.tets);
  mesh.masses.assign(4, 1.0);
  mesh.fixed.assign(4, 0);
  return mesh;
}

}  // namespace

TEST(MassSpring, FemProjectionOnARegularTet) {
  // k = V [(lambda + mu) / L^2 - mu g_a . g_b]; on a regular tet g_a . g_b = -1 / (2 L^2), so
  // k = V (lambda + 1.5 mu) / L^2: Van Gelder's E V / L^2 exactly at nu = 1/4 (lambda = mu = 0.4 E),
  // and 3.62 times it at nu = 0.45.
  const double edge = 0.1, e_modulus = 1e4, volume = edge * edge * edge / (6 * std::sqrt(2.0));
  MassSpringOptions projection;
  projection.stiffness_rule = StiffnessRule::kFemProjection;
  for (double nu : {0.25, 0.45}) {
    MsBody body(regular_tet(edge), make_material(e_modulus, nu, 1000.0), projection);
    const double lambda = e_modulus * nu / ((1 + nu) * (1 - 2 * nu)),
                 mu = e_modulus / (2 * (1 + nu));
    const double expected = volume * (lambda + 1.5 * mu) / (edge * edge);
    ASSERT_EQ(body.model->springs().size(), 6u);
    for (double k : body.model->springs().stiffness)
      EXPECT_NEAR(k, expected, 1e-9 * expected) << nu;
    if (nu == 0.25) {
      EXPECT_NEAR(expected, e_modulus * volume / (edge * edge), 1e-9 * expected);
    }
  }
  MsBody van_gelder(regular_tet(edge), make_material(e_modulus, 0.45, 1000.0));
  for (double k : van_gelder.model->springs().stiffness)  // nu is ignored by the default rule
    EXPECT_NEAR(k, e_modulus * volume / (edge * edge), 1e-9 * k);
}

TEST(MassSpring, FemProjectionMatchesTheFemEdgeBlocksOnAJitteredBox) {
  // On any mesh, each spring equals the sum over its tets of -n^T K_ab n, K_ab the linear-FEM
  // block; checked against blocks assembled here from the shape gradients, not from the model.
  TestMesh mesh = box_tet_mesh({2, 2, 2}, {0.2, 0.2, 0.2}, 1000.0);
  TestRandom random(5);
  for (double& x : mesh.positions) x += 0.01 * random.next();
  const tacta_material material = make_material(1e5, 0.4, 1000.0);
  MassSpringOptions projection;
  projection.stiffness_rule = StiffnessRule::kFemProjection;
  MsBody body(mesh, material, projection);
  const auto& springs = body.model->springs();
  std::vector<double> expected(springs.size(), 0.0);
  const double* x = mesh.positions.data();
  for (size_t t = 0; t < mesh.tets.size() / 4; ++t) {
    const uint32_t* n = &mesh.tets[4 * t];
    const auto g = tet_shape_gradients(node_position(x, n[0]), node_position(x, n[1]),
                                       node_position(x, n[2]), node_position(x, n[3]));
    const double v = std::abs(tet_signed_volume(node_position(x, n[0]), node_position(x, n[1]),
                                                node_position(x, n[2]), node_position(x, n[3])));
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const Eigen::Vector3d unit = (node_position(x, n[b]) - node_position(x, n[a])).normalized();
        const Eigen::Matrix3d block =
            v * (material.lame_lambda * g[a] * g[b].transpose() +
                 material.lame_mu * g[b] * g[a].transpose() +
                 material.lame_mu * g[a].dot(g[b]) * Eigen::Matrix3d::Identity());
        for (size_t s = 0; s < springs.size(); ++s)
          if ((springs.ends[2 * s] == std::min(n[a], n[b])) &&
              springs.ends[2 * s + 1] == std::max(n[a], n[b]))
            expected[s] -= unit.dot(block * unit);
      }
  }
  for (size_t s = 0; s < springs.size(); ++s)
    EXPECT_NEAR(springs.stiffness[s], std::max(expected[s], 0.0),
                1e-9 * std::abs(expected[s]) + 1e-12)
        << s;
}

TEST(MassSpring, EdgeNamingAMissingNodeIsRefusedByName) {
  TestMesh mesh = regular_tet(0.1);
  mesh.edges.back() = 9;  // the mesh has 4 nodes
  for (StiffnessRule rule : {StiffnessRule::kVanGelder, StiffnessRule::kFemProjection}) {
    MassSpringOptions options;
    options.stiffness_rule = rule;
    try {
      MsBody body(mesh, make_material(1e4, 0.3, 1000.0), options);
      ADD_FAILURE() << "accepted an edge to node 9";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("edge 5 (2, 9) is invalid for 4 nodes"),
                std::string::npos)
          << e.what();
    }
  }
}
