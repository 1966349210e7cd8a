#include "element_rotation.hpp"

#include <Eigen/SVD>
#include <cmath>

namespace tacta::models::corotational {

int polar_rotation(const Eigen::Matrix3d& deformation, Eigen::Quaterniond& rotation,
                   int max_iterations) {
  // Each iteration rotates R about omega, the torque that turns R's columns towards F's columns;
  // the denominator is a Gauss-Newton scale; 1e-9 keeps it finite for degenerate F.
  constexpr double kAngleTolerance = 1e-12;  // rad: below this the rotation is converged
  int iteration = 0;
  for (; iteration < max_iterations; ++iteration) {
    const Eigen::Matrix3d r = rotation.toRotationMatrix();
    Eigen::Vector3d torque = Eigen::Vector3d::Zero();
    double alignment = 0.0;
    for (int c = 0; c < 3; ++c) {
      torque += r.col(c).cross(deformation.col(c));
      alignment += r.col(c).dot(deformation.col(c));
    }
    const Eigen::Vector3d omega = torque / (std::abs(alignment) + 1e-9);
    const double angle = omega.norm();
    if (angle < kAngleTolerance) break;
    rotation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, omega / angle)) * rotation;
    rotation.normalize();
  }
  return iteration;
}

Eigen::Matrix3d svd_rotation(const Eigen::Matrix3d& deformation) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(deformation,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  Eigen::Matrix3d v = svd.matrixV();
  // Eigen sorts singular values in decreasing order: column 2 holds the smallest.
  if (u.determinant() < 0.0) u.col(2) = -u.col(2);
  if (v.determinant() < 0.0) v.col(2) = -v.col(2);
  return u * v.transpose();
}

}  // namespace tacta::models::corotational
