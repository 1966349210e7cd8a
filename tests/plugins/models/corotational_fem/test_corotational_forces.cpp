// Internal forces and stiffness of the corotational FEM: rest, rigid motions, patch test,
// symmetry and positive semi-definiteness, for both rotation methods.
#include <Eigen/Dense>
#include <cmath>
#include <gtest/gtest.h>

#include "corotational_test_support.hpp"

namespace tacta::models::corotational {
namespace {

using testing::make_model;

class CorotationalForces : public ::testing::TestWithParam<RotationMethod> {
 protected:
  TestMesh mesh = box_tet_mesh({3, 2, 4}, {0.3, 0.2, 0.4}, 1000.0);
  tacta_material material = make_material(1e5, 0.3, 1000.0);
  Options options() const {
    Options o;
    o.rotation = GetParam();
    return o;
  }
  // Largest nodal force magnitude, N.
  static double max_force(const std::vector<double>& f) {
    double m = 0.0;
    for (double v : f) m = std::max(m, std::abs(v));
    return m;
  }
  // Force scale of a unit strain on this mesh: E times a face area, N.
  double force_scale() const { return material.youngs_modulus * 0.1 * 0.1; }
};

TEST_P(CorotationalForces, ZeroAtRest) {
  auto model = make_model(mesh, material, options());
  std::vector<double> f(mesh.positions.size());
  model->internal_forces(mesh.positions.data(), f.data());
  EXPECT_LT(max_force(f), 1e-10 * force_scale());
  EXPECT_NEAR(model->elastic_energy(mesh.positions.data()), 0.0, 1e-15);
}

TEST_P(CorotationalForces, ZeroUnderRigidTranslation) {
  auto model = make_model(mesh, material, options());
  std::vector<double> x = mesh.positions, f(x.size());
  for (size_t k = 0; k < x.size(); ++k) x[k] += 0.37 * static_cast<double>(k % 3 + 1);
  model->internal_forces(x.data(), f.data());
  EXPECT_LT(max_force(f), 1e-9 * force_scale());
}

TEST_P(CorotationalForces, ZeroUnderLargeRigidRotation) {
  auto model = make_model(mesh, material, options());
  // 2 rad about a skew axis, then a shift: a linear (non-corotated) model gives large forces.
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(2.0, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
  std::vector<double> x(mesh.positions.size()), f(x.size());
  for (uint32_t i = 0; i < mesh.node_count(); ++i) {
    const Eigen::Vector3d p =
        r * node_position(mesh.positions.data(), i) + Eigen::Vector3d(0.1, -0.2, 0.3);
    for (int c = 0; c < 3; ++c) x[3 * i + c] = p[c];
  }
  model->internal_forces(x.data(), f.data());
  EXPECT_LT(max_force(f), 1e-8 * force_scale());
  EXPECT_LT(model->elastic_energy(x.data()), 1e-12);
}

TEST_P(CorotationalForces, PatchTestLinearFieldLeavesInteriorNodesFree) {
  auto model = make_model(mesh, material, options());
  Eigen::Matrix3d gradient;  // small displacement gradient, dimensionless
  gradient << 1.0, 0.5, -0.3, 0.2, -0.7, 0.4, 0.1, 0.3, 0.6;
  gradient *= 1e-4;
  std::vector<double> x(mesh.positions.size()), f(x.size());
  for (uint32_t i = 0; i < mesh.node_count(); ++i) {
    const Eigen::Vector3d p = node_position(mesh.positions.data(), i);
    const Eigen::Vector3d q = p + gradient * p + Eigen::Vector3d(1e-3, 0, 0);
    for (int c = 0; c < 3; ++c) x[3 * i + c] = q[c];
  }
  model->internal_forces(x.data(), f.data());
  double interior = 0.0, boundary = 0.0;
  for (uint32_t i = 0; i < mesh.node_count(); ++i) {
    const Eigen::Vector3d p = node_position(mesh.positions.data(), i);
    const bool inside = p.x() > 1e-9 && p.x() < 0.3 - 1e-9 && p.y() > 1e-9 && p.y() < 0.2 - 1e-9 &&
                        p.z() > 1e-9 && p.z() < 0.4 - 1e-9;
    const double magnitude = Eigen::Vector3d(f[3 * i], f[3 * i + 1], f[3 * i + 2]).norm();
    (inside ? interior : boundary) = std::max(inside ? interior : boundary, magnitude);
  }
  const double strain_force = 1e-4 * force_scale();  // what a boundary node carries, roughly
  EXPECT_GT(boundary, 0.05 * strain_force);          // the field is not trivial
  EXPECT_LT(interior, 1e-9 * strain_force);
  // Energy of a homogeneous small strain: V (mu eps:eps + lambda/2 tr(eps)^2), up to rotation
  // terms of order |gradient|^3.
  const Eigen::Matrix3d eps = 0.5 * (gradient + gradient.transpose());
  const double expected = 0.3 * 0.2 * 0.4 *
                          (material.lame_mu * eps.squaredNorm() +
                           0.5 * material.lame_lambda * eps.trace() * eps.trace());
  EXPECT_NEAR(model->elastic_energy(x.data()), expected, 1e-3 * expected);
}

TEST_P(CorotationalForces, StiffnessAtRestIsSymmetricPositiveSemiDefinite) {
  const TestMesh small = box_tet_mesh({2, 2, 2}, {0.2, 0.2, 0.2}, 1000.0);
  auto model = make_model(small, material, options());
  const BlockSparseMatrix& k = model->assemble_stiffness(small.positions.data());
  const int n = 3 * static_cast<int>(small.node_count());
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (uint32_t i = 0; i < k.node_count(); ++i)
    for (uint32_t b = k.row_starts()[i]; b < k.row_starts()[i + 1]; ++b)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {  // upper blocks stored; the lower ones are their transposes
          dense(3 * i + r, 3 * k.columns()[b] + c) = k.block(b)[3 * r + c];
          dense(3 * k.columns()[b] + c, 3 * i + r) = k.block(b)[3 * r + c];
        }
  const double scale = dense.cwiseAbs().maxCoeff();
  // Symmetry of the element blocks: each diagonal block symmetric, and K v = K^T v through the
  // product (which applies stored blocks both ways) matches the dense matrix.
  for (uint32_t i = 0; i < k.node_count(); ++i) {
    const double* d = k.block(k.diagonal_block(i));
    EXPECT_NEAR(d[1], d[3], 1e-12 * scale);
    EXPECT_NEAR(d[2], d[6], 1e-12 * scale);
    EXPECT_NEAR(d[5], d[7], 1e-12 * scale);
  }
  Eigen::VectorXd probe = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0), product(n);
  k.multiply(probe.data(), product.data());
  EXPECT_LT((product - dense * probe).cwiseAbs().maxCoeff(), 1e-12 * scale * n);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(dense);
  const Eigen::VectorXd values = eigen.eigenvalues();  // ascending
  EXPECT_GT(values[0], -1e-10 * scale);
  EXPECT_LT(std::abs(values[5]), 1e-10 * scale);  // six rigid-body modes
  EXPECT_GT(values[6], 1e-4 * scale);             // and nothing else is free
}

TEST_P(CorotationalForces, StiffnessMatchesForceDerivative) {
  // K v = -(f(x + s v) - f(x - s v)) / 2s at rest, where the rotation does not change K.
  auto model = make_model(mesh, material, options());
  const BlockSparseMatrix& k = model->assemble_stiffness(mesh.positions.data());
  std::vector<double> v(mesh.positions.size()), kv(v.size());
  for (size_t i = 0; i < v.size(); ++i) v[i] = std::sin(0.7 * static_cast<double>(i) + 0.3);
  k.multiply(v.data(), kv.data());
  const double s = 1e-7;
  std::vector<double> xp = mesh.positions, xm = mesh.positions, fp(v.size()), fm(v.size());
  for (size_t i = 0; i < v.size(); ++i) {
    xp[i] += s * v[i];
    xm[i] -= s * v[i];
  }
  model->internal_forces(xp.data(), fp.data());
  model->internal_forces(xm.data(), fm.data());
  double error = 0.0, norm = 0.0;
  for (size_t i = 0; i < v.size(); ++i) {
    error = std::max(error, std::abs(kv[i] + (fp[i] - fm[i]) / (2 * s)));
    norm = std::max(norm, std::abs(kv[i]));
  }
  EXPECT_LT(error, 1e-5 * norm);
}

INSTANTIATE_TEST_SUITE_P(Rotation, CorotationalForces,
                         ::testing::Values(RotationMethod::kPolar, RotationMethod::kSvd),
                         [](const auto& param_info) {
                           return param_info.param == RotationMethod::kPolar ? "polar" : "svd";
                         });

}  // namespace
}  // namespace tacta::models::corotational
