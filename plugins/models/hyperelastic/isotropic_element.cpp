#include "isotropic_element.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>

namespace tacta::models::hyperelastic {

namespace {
constexpr int kPairI[3] = {0, 0, 1};
constexpr int kPairJ[3] = {1, 2, 2};
constexpr double kCloseStretches = 1e-6;  // |s_i -+ s_j| below this: the limit formula
}  // namespace

StretchFrame rotation_variant_svd(const Eigen::Matrix3d& deformation) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(deformation, Eigen::ComputeFullU | Eigen::ComputeFullV);
  StretchFrame frame{svd.matrixU(), svd.matrixV(), svd.singularValues()};
  // Reflections go into the smallest stretch (Eigen sorts them in decreasing order).
  if (frame.u.determinant() < 0.0) {
    frame.u.col(2) *= -1.0;
    frame.sigma[2] *= -1.0;
  }
  if (frame.v.determinant() < 0.0) {
    frame.v.col(2) *= -1.0;
    frame.sigma[2] *= -1.0;
  }
  return frame;
}

DiagonalTangent diagonal_tangent(const Eigen::Vector3d& sigma, const StretchDerivatives& psi,
                                 bool project) {
  DiagonalTangent t;
  t.scaling = psi.hessian;
  for (int p = 0; p < 3; ++p) {
    const int i = kPairI[p], j = kPairJ[p];
    const double gi = psi.gradient[i], gj = psi.gradient[j];
    const double difference = sigma[i] - sigma[j];
    t.flip[p] = std::abs(difference) > kCloseStretches
                    ? (gi - gj) / difference
                    : 0.5 * (psi.hessian(i, i) + psi.hessian(j, j)) - psi.hessian(i, j);
    double sum = sigma[i] + sigma[j];
    if (std::abs(sum) < kCloseStretches) sum = sum < 0.0 ? -kCloseStretches : kCloseStretches;
    t.twist[p] = (gi + gj) / sum;
  }
  if (!project) return t;
  for (int p = 0; p < 3; ++p) {
    t.flip[p] = std::max(t.flip[p], 0.0);
    t.twist[p] = std::max(t.twist[p], 0.0);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(t.scaling);
  if (eigen.eigenvalues().minCoeff() < 0.0)
    t.scaling = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
                eigen.eigenvectors().transpose();
  return t;
}

Eigen::Matrix3d stiffness_block(const StretchFrame& frame, const DiagonalTangent& tangent,
                                const Eigen::Vector3d& wa, const Eigen::Vector3d& wb,
                                double volume) {
  Eigen::Matrix3d d = wa.asDiagonal() * tangent.scaling * wb.asDiagonal();
  for (int p = 0; p < 3; ++p) {
    const int i = kPairI[p], j = kPairJ[p];
    const double same = 0.5 * (tangent.twist[p] + tangent.flip[p]);
    const double cross = 0.5 * (tangent.flip[p] - tangent.twist[p]);
    d(i, i) += same * wa[j] * wb[j];
    d(j, j) += same * wa[i] * wb[i];
    d(i, j) += cross * wa[j] * wb[i];
    d(j, i) += cross * wa[i] * wb[j];
  }
  return volume * (frame.u * d * frame.u.transpose());
}

}  // namespace tacta::models::hyperelastic
