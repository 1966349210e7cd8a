#include "invariant_stress.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace tacta::models::hyperelastic {

bool invariant_stress(const MaterialConstants& m, const Eigen::Matrix3d& f, double& energy,
                      Eigen::Matrix3d* stress) noexcept {
  if (m.law == MaterialLaw::kStVenantKirchhoff) return false;
  Eigen::Matrix3d cofactor;  // cof(F) = J F^-T = dJ/dF
  cofactor.col(0) = f.col(1).cross(f.col(2));
  cofactor.col(1) = f.col(2).cross(f.col(0));
  cofactor.col(2) = f.col(0).cross(f.col(1));
  const double j = f.col(0).dot(cofactor.col(0));
  const Eigen::Matrix3d c = f.transpose() * f;
  const double i1 = c.trace();
  const double i2 = 0.5 * (i1 * i1 - c.squaredNorm());  // C is symmetric: C:C = |C|^2
  // sigma_min >= J / sqrt(I2) >= min_stretch: no stretch is clamped (J > 0: none inverted).
  if (!(j > 0.0) || j * j < m.min_stretch * m.min_stretch * i2) return false;
  if (m.law == MaterialLaw::kNeoHookean) {
    const double log_j = std::log(j);
    energy = 0.5 * m.mu * (i1 - 3.0) - m.mu * log_j + 0.5 * m.lambda * log_j * log_j;
    if (stress != nullptr) *stress = m.mu * f + ((m.lambda * log_j - m.mu) / j) * cofactor;
    return true;
  }
  const double j23 = std::cbrt(1.0 / (j * j));  // J^-2/3
  const double j43 = j23 * j23;
  energy =
      m.c10 * (j23 * i1 - 3.0) + m.c01 * (j43 * i2 - 3.0) + 0.5 * m.bulk * (j - 1.0) * (j - 1.0);
  if (stress != nullptr) {
    const double inverse_j = 1.0 / j;
    *stress = (2.0 * m.c10 * j23 + 2.0 * m.c01 * j43 * i1) * f - (2.0 * m.c01 * j43) * (f * c) +
              (-(2.0 / 3.0) * m.c10 * j23 * i1 * inverse_j -
               (4.0 / 3.0) * m.c01 * j43 * i2 * inverse_j + m.bulk * (j - 1.0)) *
                  cofactor;
  }
  return true;
}

}  // namespace tacta::models::hyperelastic
