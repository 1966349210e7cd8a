#include "isotropic_element.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace tacta::models::hyperelastic {

namespace {
constexpr int kPairI[3] = {0, 0, 1};
constexpr int kPairJ[3] = {1, 2, 2};
constexpr double kCloseStretches = 1e-6;  // |s_i -+ s_j| below this: the limit formula
constexpr double kDegenerate = 1e-12;     // a stretch this small has no direction of its own
}  // namespace

StretchFrame rotation_variant_svd(const Eigen::Matrix3d& deformation) {
  // From the eigen-decomposition of C = F^T F in closed form (several times cheaper than a
  // Jacobi SVD): V and sigma^2, then U's columns from F v_i / sigma_i, the last one as a cross
  // product so that U is a rotation, and the smallest stretch signed by u_2 . F v_2.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(deformation.transpose() * deformation);
  StretchFrame frame;
  for (int i = 0; i < 3; ++i) {  // decreasing order: the smallest stretch last
    frame.v.col(i) = eigen.eigenvectors().col(2 - i);
    frame.sigma[i] = std::sqrt(std::max(eigen.eigenvalues()[2 - i], 0.0));
  }
  if (frame.v.determinant() < 0.0) frame.v.col(2) *= -1.0;
  const Eigen::Vector3d f0 = deformation * frame.v.col(0);
  frame.u.col(0) = frame.sigma[0] > kDegenerate ? Eigen::Vector3d(f0 / frame.sigma[0])
                                                : Eigen::Vector3d::UnitX();
  Eigen::Vector3d f1 = deformation * frame.v.col(1);
  f1 -= frame.u.col(0).dot(f1) * frame.u.col(0);
  if (f1.norm() > kDegenerate * std::max(1.0, frame.sigma[0])) {
    frame.u.col(1) = f1.normalized();
  } else {  // F is (nearly) rank one: any unit vector orthogonal to u_0
    const Eigen::Vector3d axis =
        std::abs(frame.u(0, 0)) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    frame.u.col(1) = frame.u.col(0).cross(axis).normalized();
  }
  frame.u.col(2) = frame.u.col(0).cross(frame.u.col(1));
  frame.sigma[2] = frame.u.col(2).dot(deformation * frame.v.col(2));
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
  // Positive definite (Sylvester's leading minors) is the common case: no eigen-decomposition.
  const Eigen::Matrix3d& h = t.scaling;
  if (h(0, 0) > 0.0 && h(0, 0) * h(1, 1) - h(0, 1) * h(1, 0) > 0.0 && h.determinant() > 0.0)
    return t;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(t.scaling);
  if (eigen.eigenvalues().minCoeff() < 0.0)
    t.scaling = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
                eigen.eigenvectors().transpose();
  return t;
}

void element_stiffness(const StretchFrame& frame, const DiagonalTangent& tangent,
                       const Eigen::Vector3d (&w)[4], double volume,
                       Eigen::Matrix3d (&blocks)[10]) {
  // The modes' weights times the volume once, not per block.
  const Eigen::Matrix3d scaling = volume * tangent.scaling;
  double same[3], cross[3];
  for (int p = 0; p < 3; ++p) {
    same[p] = 0.5 * volume * (tangent.twist[p] + tangent.flip[p]);
    cross[p] = 0.5 * volume * (tangent.flip[p] - tangent.twist[p]);
  }
  // K(wa, wb) = U d U^T with d the tangent in U's frame, bilinear in wa and wb.
  const auto block = [&](const Eigen::Vector3d& wa, const Eigen::Vector3d& wb) {
    Eigen::Matrix3d d = wa.asDiagonal() * scaling * wb.asDiagonal();
    for (int p = 0; p < 3; ++p) {
      const int i = kPairI[p], j = kPairJ[p];
      d(i, i) += same[p] * wa[j] * wb[j];
      d(j, j) += same[p] * wa[i] * wb[i];
      d(i, j) += cross[p] * wa[j] * wb[i];
      d(j, i) += cross[p] * wa[i] * wb[j];
    }
    return Eigen::Matrix3d(frame.u * d * frame.u.transpose());
  };
  blocks[0] = block(w[0], w[0]);
  blocks[1] = block(w[0], w[1]);
  blocks[2] = block(w[0], w[2]);
  blocks[4] = block(w[1], w[1]);
  blocks[5] = block(w[1], w[2]);
  blocks[7] = block(w[2], w[2]);
  // w_3 = -(w_0 + w_1 + w_2), and K_ba = K_ab^T.
  blocks[3] = -(blocks[0] + blocks[1] + blocks[2]);
  blocks[6] = -(blocks[1].transpose() + blocks[4] + blocks[5]);
  blocks[8] = -(blocks[2].transpose() + blocks[5].transpose() + blocks[7]);
  blocks[9] = -(blocks[3].transpose() + blocks[6].transpose() + blocks[8].transpose()).eval();
}

}  // namespace tacta::models::hyperelastic
