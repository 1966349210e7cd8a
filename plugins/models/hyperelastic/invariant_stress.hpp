// Energy density and first Piola-Kirchhoff stress straight from F's invariants, with no SVD:
// what a force-only element pass (line search, residual) needs. Valid only where the stretch
// clamp of stretch_energy.hpp cannot act, which a cheap bound proves: the smallest eigenvalue
// of C = F^T F is at least det C / I2(C), so sigma_min >= J / sqrt(I2(C)). Elsewhere (and for
// stvk, whose clamp at 1/sqrt(3) the bound does not clear near rest) the caller takes the SVD
// path; both give the same energy and stress up to rounding.
//   neo_hookean   P = mu F + (lambda ln J - mu) F^-T
//   mooney_rivlin P = C10 J^-2/3 (2 F - 2/3 I1 F^-T) + C01 J^-4/3 (2 (I1 F - F C) - 4/3 I2 F^-T)
//                     + K (J - 1) J F^-T
#pragma once

#include <Eigen/Core>

#include "stretch_energy.hpp"

namespace tacta::models::hyperelastic {

// Writes psi (J/m^3) and, if stress is not null, P (Pa); false (nothing written) where the
// SVD path must be taken.
bool invariant_stress(const MaterialConstants& material, const Eigen::Matrix3d& deformation,
                      double& energy, Eigen::Matrix3d* stress) noexcept;

}  // namespace tacta::models::hyperelastic
