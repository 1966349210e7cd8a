// The two tet energies of the vbd model, per element and per corner: what a vertex's Newton
// step needs (the force on one corner and its 3x3 Hessian block) and what queries need (energy,
// the stress whose product with a shape gradient gives a corner's force). F is the deformation
// gradient (dimensionless), stresses are first Piola-Kirchhoff (Pa), energies densities (J/m^3).
#pragma once

#include <Eigen/Core>

#include "tacta/models/lame.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::vbd {

// F = sum_a x_a grad N_a^T of a tet at positions (3 per node, m).
Eigen::Matrix3d tet_deformation(const TetRest& tet, const double* positions) noexcept;

inline Eigen::Vector3d corner_gradient(const TetRest& tet, int corner) noexcept {
  return {tet.gradients[corner][0], tet.gradients[corner][1], tet.gradients[corner][2]};
}

// Corotational (corotational_fem's energy): eps = sym(R^T F) - I,
// psi = mu eps:eps + lambda/2 tr(eps)^2, P = R (2 mu eps + lambda tr(eps) I). With R the polar
// rotation of F this is the exact gradient; with R held fixed it is the gradient of a quadratic.
Eigen::Matrix3d corotational_stress(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r,
                                    const Lame& lame) noexcept;
double corotational_energy_density(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r,
                                   const Lame& lame) noexcept;
// One corner's force -V R (2 mu eps + lambda tr(eps) I) g: the stress product above, cheaper.
Eigen::Vector3d corotational_corner_force(const TetRest& tet, int corner, const Eigen::Matrix3d& f,
                                          const Eigen::Matrix3d& r, const Lame& lame) noexcept;
// Corner block of R K0 R^T (fixed R): V R [mu |g|^2 I + (lambda + mu) g g^T] R^T, SPD.
Eigen::Matrix3d corotational_corner_hessian(const TetRest& tet, int corner,
                                            const Eigen::Matrix3d& r, const Lame& lame) noexcept;

// Neo-Hookean: psi = mu/2 (I1 - 3) + U(J), U(J) = -mu ln J + lambda/2 ln^2 J for
// J >= min_ratio, its second-order Taylor expansion about min_ratio below.
struct VolumeTerm {
  double energy, slope, curvature;  // U (Pa), dU/dJ (Pa), d2U/dJ2 (Pa)
};
VolumeTerm neo_hookean_volume_term(double j, const Lame& lame, double min_ratio) noexcept;
// P = mu F + U'(J) cof(F), cof(F) = dJ/dF.
Eigen::Matrix3d neo_hookean_stress(const Eigen::Matrix3d& f, const Lame& lame,
                                   double min_ratio) noexcept;
double neo_hookean_energy_density(const Eigen::Matrix3d& f, const Lame& lame,
                                  double min_ratio) noexcept;
// One corner's force -V P g and exact Hessian block V (mu |g|^2 I + U''(J) b b^T), b = cof(F) g
// = dJ/dx (J is linear in one vertex's position, so no other term), with U'' clamped at 0.
void neo_hookean_corner(const TetRest& tet, int corner, const Eigen::Matrix3d& f, const Lame& lame,
                        double min_ratio, Eigen::Vector3d& force,
                        Eigen::Matrix3d* hessian) noexcept;

}  // namespace tacta::models::vbd
