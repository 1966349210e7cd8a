// One linear tetrahedron of an isotropic hyperelastic material: the deformation gradient's
// rotation-variant SVD, the first Piola-Kirchhoff stress, and the stiffness blocks from the
// tangent dP/dF written in its eigenmodes (Teran et al. 2005; Smith et al. 2019): three
// scaling modes from the Hessian in the stretches, and per pair of axes a twist and a flip mode
// with eigenvalues (g_i + g_j) / (s_i + s_j) and (g_i - g_j) / (s_i - s_j). Projecting negative
// eigenvalues to zero keeps every element's stiffness positive semi-definite, inverted or not.
#pragma once

#include <Eigen/Core>

#include "stretch_energy.hpp"

namespace tacta::models::hyperelastic {

// F = U diag(sigma) V^T with U and V rotations; an inverted F has sigma[2] < 0.
struct StretchFrame {
  Eigen::Matrix3d u, v;
  Eigen::Vector3d sigma;
};
StretchFrame rotation_variant_svd(const Eigen::Matrix3d& deformation);

// dP/dF in the frame of U and V: scaling block (3x3 over sigma) and per pair (0,1), (0,2),
// (1,2) the twist and flip eigenvalues, Pa.
struct DiagonalTangent {
  Eigen::Matrix3d scaling;
  double twist[3], flip[3];
};
DiagonalTangent diagonal_tangent(const Eigen::Vector3d& sigma, const StretchDerivatives& psi,
                                 bool project);

// P = U diag(dpsi/dsigma) V^T, Pa.
inline Eigen::Matrix3d first_piola(const StretchFrame& frame, const StretchDerivatives& psi) {
  return frame.u * psi.gradient.asDiagonal() * frame.v.transpose();
}

// The element's ten node-pair blocks K_ab = volume * sum over modes of lambda (Q g_a)(Q g_b)^T,
// a <= b in the order (0,0) (0,1) (0,2) (0,3) (1,1) (1,2) (1,3) (2,2) (2,3) (3,3), given
// w_a = V^T g_a (1/m): N/m. The gradients of a tet sum to zero, so the six blocks among nodes
// 0-2 are computed and those with node 3 follow as sums (K_a3 = -sum_c K_ac).
void element_stiffness(const StretchFrame& frame, const DiagonalTangent& tangent,
                       const Eigen::Vector3d (&w)[4], double volume, Eigen::Matrix3d (&blocks)[10]);

}  // namespace tacta::models::hyperelastic
