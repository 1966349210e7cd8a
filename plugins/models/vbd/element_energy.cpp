#include "element_energy.hpp"

namespace tacta::models::vbd {

Eigen::Matrix3d tet_deformation(const TetRest& tet, const double* positions) noexcept {
  // grad N_0 = -(grad N_1 + grad N_2 + grad N_3): F = sum_{a>0} (x_a - x_0) grad N_a^T.
  const double* x0 = positions + 3 * size_t{tet.nodes[0]};
  Eigen::Matrix3d f = Eigen::Matrix3d::Zero();
  for (int a = 1; a < 4; ++a) {
    const double* xa = positions + 3 * size_t{tet.nodes[a]};
    const double d[3] = {xa[0] - x0[0], xa[1] - x0[1], xa[2] - x0[2]};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) f(r, c) += d[r] * tet.gradients[a][c];
  }
  return f;
}

Eigen::Matrix3d corotational_stress(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r,
                                    const Lame& lame) noexcept {
  const Eigen::Matrix3d g = r.transpose() * f;
  Eigen::Matrix3d eps = 0.5 * (g + g.transpose());  // sym(R^T F) - I
  eps.diagonal().array() -= 1.0;
  Eigen::Matrix3d sigma = 2.0 * lame.mu * eps;
  sigma.diagonal().array() += lame.lambda * eps.trace();
  return r * sigma;
}

double corotational_energy_density(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r,
                                   const Lame& lame) noexcept {
  const Eigen::Matrix3d g = r.transpose() * f;
  Eigen::Matrix3d eps = 0.5 * (g + g.transpose());
  eps.diagonal().array() -= 1.0;
  const double trace = eps.trace();
  return lame.mu * eps.squaredNorm() + 0.5 * lame.lambda * trace * trace;
}

Eigen::Matrix3d neo_hookean_stress(const Eigen::Matrix3d& f, const Lame& lame,
                                   double min_ratio) noexcept {
  const Eigen::Matrix3d cof = cofactor(f);
  const double j = f.col(0).dot(cof.col(0));
  return lame.mu * f + neo_hookean_volume_term(j, lame, min_ratio).slope * cof;
}

double neo_hookean_energy_density(const Eigen::Matrix3d& f, const Lame& lame,
                                  double min_ratio) noexcept {
  return 0.5 * lame.mu * (f.squaredNorm() - 3.0) +
         neo_hookean_volume_term(f.determinant(), lame, min_ratio).energy;
}

}  // namespace tacta::models::vbd
