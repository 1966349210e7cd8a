// The two tet energies of the vbd model, per element and per corner: what a vertex's Newton
// step needs (the force on one corner and its 3x3 Hessian block; inline, the sweeps' inner
// loop) and what queries need (energy, the stress whose product with a shape gradient gives a
// corner's force). F is the deformation gradient (dimensionless), stresses are first
// Piola-Kirchhoff (Pa), energies densities (J/m^3), forces N, Hessian blocks N/m.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "tacta/models/lame.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::vbd {

// The corner terms run ~40 times per vertex step: inlined into the sweep whatever GCC's
// heuristics say (a call per corner cost a third of the step).
#if defined(__GNUC__)
#define TACTA_VBD_INLINE inline __attribute__((always_inline))
#else
#define TACTA_VBD_INLINE inline
#endif

// F = sum_a x_a grad N_a^T of a tet at positions (3 per node, m).
Eigen::Matrix3d tet_deformation(const TetRest& tet, const double* positions) noexcept;

TACTA_VBD_INLINE Eigen::Vector3d corner_gradient(const TetRest& tet, int corner) noexcept {
  return {tet.gradients[corner][0], tet.gradients[corner][1], tet.gradients[corner][2]};
}

// Corotational (corotational_fem's energy): eps = sym(R^T F) - I,
// psi = mu eps:eps + lambda/2 tr(eps)^2, P = R (2 mu eps + lambda tr(eps) I). With R the polar
// rotation of F this is the exact gradient; with R held fixed it is the gradient of a quadratic.
Eigen::Matrix3d corotational_stress(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r,
                                    const Lame& lame) noexcept;
double corotational_energy_density(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r,
                                   const Lame& lame) noexcept;

// The corner terms take the corner's shape gradient g = grad N_a (1/m) and the tet's rest
// volume V (m^3).
// One corner's force -V R (2 mu eps + lambda tr(eps) I) g, from G = R^T F (the deformation
// in the tet's rotated frame, which the sweep keeps): eps g = (G g + G^T g) / 2 - g and
// tr(eps) = tr(G) - 3, no 3x3 product. Written out on the column-major arrays: the sweep's
// innermost work, where Eigen's temporaries cost twice the instructions.
TACTA_VBD_INLINE Eigen::Vector3d corotational_corner_force(const Eigen::Vector3d& g, double volume,
                                                           const Eigen::Matrix3d& rotated,
                                                           const Eigen::Matrix3d& r,
                                                           const Lame& lame) noexcept {
  const double* m = rotated.data();  // G(i, j) = m[i + 3 j]
  const double trace = m[0] + m[4] + m[8] - 3.0;
  double s[3];
  for (int i = 0; i < 3; ++i) {
    const double gg = m[i] * g[0] + m[i + 3] * g[1] + m[i + 6] * g[2];               // (G g)_i
    const double gtg = m[3 * i] * g[0] + m[3 * i + 1] * g[1] + m[3 * i + 2] * g[2];  // (G^T g)_i
    s[i] = lame.mu * (gg + gtg - 2.0 * g[i]) + lame.lambda * trace * g[i];
  }
  const double* q = r.data();  // R(i, j) = q[i + 3 j]
  return {-volume * (q[0] * s[0] + q[3] * s[1] + q[6] * s[2]),
          -volume * (q[1] * s[0] + q[4] * s[1] + q[7] * s[2]),
          -volume * (q[2] * s[0] + q[5] * s[1] + q[8] * s[2])};
}

// Corner block of R K0 R^T (fixed R): V R [mu |g|^2 I + (lambda + mu) g g^T] R^T, SPD.
TACTA_VBD_INLINE Eigen::Matrix3d corotational_corner_hessian(const Eigen::Vector3d& g,
                                                             double volume,
                                                             const Eigen::Matrix3d& r,
                                                             const Lame& lame) noexcept {
  const Eigen::Vector3d rg = r * g;  // |R g| = |g|
  Eigen::Matrix3d k = (lame.lambda + lame.mu) * rg * rg.transpose();
  k.diagonal().array() += lame.mu * rg.squaredNorm();
  return volume * k;
}

// Neo-Hookean: psi = mu/2 (I1 - 3) + U(J), U(J) = -mu ln J + lambda/2 ln^2 J for
// J >= min_ratio, its second-order Taylor expansion about min_ratio below.
struct VolumeTerm {
  double energy, slope, curvature;  // U (Pa), dU/dJ (Pa), d2U/dJ2 (Pa)
};
TACTA_VBD_INLINE VolumeTerm neo_hookean_volume_term(double j, const Lame& lame,
                                                    double min_ratio) noexcept {
  const double lambda = lame.lambda, mu = lame.mu;
  const double jc = std::max(j, min_ratio), ln = std::log(jc);
  const VolumeTerm at{-mu * ln + 0.5 * lambda * ln * ln, (lambda * ln - mu) / jc,
                      (mu + lambda - lambda * ln) / (jc * jc)};
  if (j >= min_ratio) return at;
  const double d = j - min_ratio;
  return {at.energy + at.slope * d + 0.5 * at.curvature * d * d, at.slope + at.curvature * d,
          at.curvature};
}

// cof(F) = dJ/dF: column c is the cross product of the other two columns of F.
TACTA_VBD_INLINE Eigen::Matrix3d cofactor(const Eigen::Matrix3d& f) noexcept {
  Eigen::Matrix3d c;
  c.col(0) = f.col(1).cross(f.col(2));
  c.col(1) = f.col(2).cross(f.col(0));
  c.col(2) = f.col(0).cross(f.col(1));
  return c;
}

// P = mu F + U'(J) cof(F).
Eigen::Matrix3d neo_hookean_stress(const Eigen::Matrix3d& f, const Lame& lame,
                                   double min_ratio) noexcept;
double neo_hookean_energy_density(const Eigen::Matrix3d& f, const Lame& lame,
                                  double min_ratio) noexcept;

// One corner's force -V P g and exact Hessian block V (mu |g|^2 I + U''(J) b b^T), b = cof(F) g
// = dJ/dx (J is linear in one vertex's position, so no other term), with U'' clamped at 0.
TACTA_VBD_INLINE void neo_hookean_corner(const Eigen::Vector3d& g, double volume,
                                         const Eigen::Matrix3d& f, const Lame& lame,
                                         double min_ratio, Eigen::Vector3d& force,
                                         Eigen::Matrix3d* hessian) noexcept {
  const Eigen::Matrix3d cof = cofactor(f);
  const double j = f.col(0).dot(cof.col(0));
  const Eigen::Vector3d b = cof * g;  // dJ/dx of this corner, 1/m
  const VolumeTerm u = neo_hookean_volume_term(j, lame, min_ratio);
  force = -volume * (lame.mu * (f * g) + u.slope * b);
  if (hessian == nullptr) return;
  // U'' < 0 only where lambda ln J > mu + lambda (J > e^(1 + mu/lambda), a 2.7x stretch):
  // dropping it keeps the block positive definite (the paper's SPD projection).
  *hessian = std::max(u.curvature, 0.0) * b * b.transpose();
  hessian->diagonal().array() += lame.mu * g.squaredNorm();
  *hessian *= volume;
}

}  // namespace tacta::models::vbd
