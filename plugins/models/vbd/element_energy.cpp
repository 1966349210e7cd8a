#include "element_energy.hpp"

#include <algorithm>
#include <cmath>

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

namespace {
// eps = sym(R^T F) - I.
Eigen::Matrix3d corotational_strain(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r) noexcept {
  const Eigen::Matrix3d g = r.transpose() * f;
  Eigen::Matrix3d eps = 0.5 * (g + g.transpose());
  eps.diagonal().array() -= 1.0;
  return eps;
}
}  // namespace

Eigen::Matrix3d corotational_stress(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r,
                                    const Lame& lame) noexcept {
  const Eigen::Matrix3d eps = corotational_strain(f, r);
  Eigen::Matrix3d sigma = 2.0 * lame.mu * eps;
  sigma.diagonal().array() += lame.lambda * eps.trace();
  return r * sigma;
}

Eigen::Vector3d corotational_corner_force(const TetRest& tet, int corner, const Eigen::Matrix3d& f,
                                          const Eigen::Matrix3d& r, const Lame& lame) noexcept {
  const Eigen::Matrix3d eps = corotational_strain(f, r);
  const Eigen::Vector3d g = corner_gradient(tet, corner);
  const Eigen::Vector3d sigma_g = 2.0 * lame.mu * (eps * g) + lame.lambda * eps.trace() * g;
  return -tet.volume * (r * sigma_g);
}

double corotational_energy_density(const Eigen::Matrix3d& f, const Eigen::Matrix3d& r,
                                   const Lame& lame) noexcept {
  const Eigen::Matrix3d eps = corotational_strain(f, r);
  const double trace = eps.trace();
  return lame.mu * eps.squaredNorm() + 0.5 * lame.lambda * trace * trace;
}

Eigen::Matrix3d corotational_corner_hessian(const TetRest& tet, int corner,
                                            const Eigen::Matrix3d& r, const Lame& lame) noexcept {
  const Eigen::Vector3d rg = r * corner_gradient(tet, corner);  // R g: |R g| = |g|
  Eigen::Matrix3d k = (lame.lambda + lame.mu) * rg * rg.transpose();
  k.diagonal().array() += lame.mu * rg.squaredNorm();
  return tet.volume * k;
}

VolumeTerm neo_hookean_volume_term(double j, const Lame& lame, double min_ratio) noexcept {
  const double lambda = lame.lambda, mu = lame.mu;
  const double jc = std::max(j, min_ratio), ln = std::log(jc);
  const VolumeTerm at{-mu * ln + 0.5 * lambda * ln * ln, (lambda * ln - mu) / jc,
                      (mu + lambda - lambda * ln) / (jc * jc)};
  if (j >= min_ratio) return at;
  const double d = j - min_ratio;
  return {at.energy + at.slope * d + 0.5 * at.curvature * d * d, at.slope + at.curvature * d,
          at.curvature};
}

namespace {
// cof(F) = [f1 x f2 ... ]: column c is the cross product of the other two columns of F.
Eigen::Matrix3d cofactor(const Eigen::Matrix3d& f) noexcept {
  Eigen::Matrix3d c;
  c.col(0) = f.col(1).cross(f.col(2));
  c.col(1) = f.col(2).cross(f.col(0));
  c.col(2) = f.col(0).cross(f.col(1));
  return c;
}
}  // namespace

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

void neo_hookean_corner(const TetRest& tet, int corner, const Eigen::Matrix3d& f, const Lame& lame,
                        double min_ratio, Eigen::Vector3d& force,
                        Eigen::Matrix3d* hessian) noexcept {
  const Eigen::Vector3d g = corner_gradient(tet, corner);
  const Eigen::Matrix3d cof = cofactor(f);
  const double j = f.col(0).dot(cof.col(0));
  const Eigen::Vector3d b = cof * g;  // dJ/dx of this corner, 1/m
  const VolumeTerm u = neo_hookean_volume_term(j, lame, min_ratio);
  force = -tet.volume * (lame.mu * (f * g) + u.slope * b);
  if (hessian == nullptr) return;
  // U'' < 0 only where lambda ln J > mu + lambda (J > e^(1 + mu/lambda), a 2.7x stretch):
  // dropping it keeps the block positive definite (the paper's SPD projection).
  *hessian = std::max(u.curvature, 0.0) * b * b.transpose();
  hessian->diagonal().array() += lame.mu * g.squaredNorm();
  *hessian *= tet.volume;
}

}  // namespace tacta::models::vbd
