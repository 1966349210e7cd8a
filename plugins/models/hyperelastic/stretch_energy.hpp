// Isotropic hyperelastic energy densities written in the principal stretches sigma (the
// singular values of F, sigma_3 negative when the element is inverted), with their gradient and
// Hessian in sigma: everything the element needs for stress and a consistent tangent.
//   neo_hookean   psi = mu/2 (I1 - 3) - mu ln J + lambda/2 (ln J)^2           (compressible)
//   stvk          psi = mu E:E + lambda/2 tr(E)^2, E = (F^T F - I) / 2           (St Venant-Kirchhoff)
//   mooney_rivlin psi = C10 (J^-2/3 I1 - 3) + C01 (J^-4/3 I2 - 3) + K/2 (J - 1)^2
// with I1 = sum sigma_i^2, I2 = sum_{i<j} sigma_i^2 sigma_j^2, J = sigma_1 sigma_2 sigma_3.
// Units: psi in J/m^3 (Pa), moduli in Pa. Below min_stretch (where ln J and J^-2/3 blow up or
// an element inverts; for stvk below 1/sqrt(3), where it softens) the energy continues as its
// second-order Taylor expansion about the clamped stretches, with the Hessian's negative
// eigenvalues dropped: finite, and rising the further an element is crushed (invertible FEM).
// The continuation's gradient uses the clamped point's Hessian, so there the tangent is the
// energy's up to the Hessian's change along the clamp.
#pragma once

#include <Eigen/Core>

namespace tacta::models::hyperelastic {

enum class MaterialLaw { kNeoHookean = 0, kStVenantKirchhoff = 1, kMooneyRivlin = 2 };

struct MaterialConstants {
  MaterialLaw law = MaterialLaw::kNeoHookean;
  double mu = 0.0, lambda = 0.0;            // Pa: neo_hookean and stvk
  double c10 = 0.0, c01 = 0.0, bulk = 0.0;  // Pa: mooney_rivlin
  double min_stretch = 0.1;  // principal stretches are clamped here before evaluation
};

struct StretchDerivatives {
  double energy = 0.0;                                 // J/m^3
  Eigen::Vector3d gradient = Eigen::Vector3d::Zero();  // d psi / d sigma_i, Pa
  Eigen::Matrix3d hessian = Eigen::Matrix3d::Zero();   // d2 psi / d sigma_i d sigma_j, Pa
};

// Exact derivatives at sigma (no clamping).
StretchDerivatives stretch_derivatives(const MaterialConstants& material,
                                       const Eigen::Vector3d& sigma);
// With the clamp and its Taylor continuation below min_stretch.
StretchDerivatives clamped_stretch_derivatives(const MaterialConstants& material,
                                               const Eigen::Vector3d& sigma);
// Energy only (line searches): the same value as clamped_stretch_derivatives().energy.
double clamped_stretch_energy(const MaterialConstants& material, const Eigen::Vector3d& sigma);

}  // namespace tacta::models::hyperelastic
