#include "element_rotation.hpp"

#include <Eigen/SVD>
#include <cmath>

#include "hot_path.hpp"

namespace tacta::models::corotational {

TACTA_HOT_PATH int polar_rotation(const Eigen::Matrix3d& deformation, Eigen::Quaterniond& rotation,
                                  int max_iterations) {
  // Maximise tr(R^T F) over R' = exp([w]) R. With B = F R^T, the gradient in w is the torque
  // axial(B - B^T) = sum_i r_i x f_i and the Hessian is -(tr(B) I - sym(B)): a Newton step
  // solves (tr(B) I - sym(B)) w = torque and converges quadratically near the answer. Far from
  // it (that matrix not positive definite, e.g. inverted elements) the step falls back to
  // Mueller et al.'s safe scale w = torque / |tr(B)|, which always turns towards F.
  constexpr double kAngleTolerance2 = 1e-24;  // rad^2: a 1e-12 rad correction is converged
  // After a Newton step of |omega| rad the error left is of order |omega|^2: a step under
  // 1e-6 rad leaves about 1e-12 rad, so the loop ends without re-measuring the torque (that
  // check cost a third of the polar time with a warm start).
  constexpr double kNewtonFinalStep2 = 1e-12;  // rad^2
  int iteration = 0;
  while (iteration < max_iterations) {
    const Eigen::Matrix3d b = deformation * rotation.toRotationMatrix().transpose();
    const Eigen::Vector3d torque(b(2, 1) - b(1, 2), b(0, 2) - b(2, 0), b(1, 0) - b(0, 1));
    const double trace = b.trace();
    // Near the answer the Hessian is about 2 I (B close to I): stop before inverting it.
    if (torque.squaredNorm() < 4.0 * kAngleTolerance2 * (trace * trace) / 9.0) break;
    Eigen::Matrix3d hessian = -0.5 * (b + b.transpose());
    hessian.diagonal().array() += trace;
    // Positive definite by leading minors; otherwise take the safe gradient step.
    const double m1 = hessian(0, 0);
    const double m2 = hessian(0, 0) * hessian(1, 1) - hessian(0, 1) * hessian(1, 0);
    const double m3 = hessian.determinant();
    Eigen::Vector3d omega;
    const bool newton = m1 > 0.0 && m2 > 0.0 && m3 > 1e-12 * m1 * m1 * m1;
    if (newton)
      omega = hessian.inverse() * torque;
    else
      omega = torque / (std::abs(trace) + 1e-9);
    // Rotate by omega without trigonometry: q += (0, omega/2) q, then renormalise. That turns
    // by 2 atan(|omega|/2) about the same axis: exact to second order, same fixed point.
    const Eigen::Quaterniond turn(0.0, 0.5 * omega.x(), 0.5 * omega.y(), 0.5 * omega.z());
    rotation.coeffs() += (turn * rotation).coeffs();
    rotation.normalize();
    ++iteration;
    if (newton && omega.squaredNorm() < kNewtonFinalStep2) break;
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
