#include "stretch_energy.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace tacta::models::hyperelastic {

namespace {

// A value with its gradient and Hessian in the three stretches: second-order forward
// differentiation, so Mooney-Rivlin's isochoric terms need no hand-derived Hessian.
struct Jet {
  double v = 0.0;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
};
Jet variable(double value, int index) {
  Jet j;
  j.v = value;
  j.g[index] = 1.0;
  return j;
}
Jet operator+(const Jet& a, const Jet& b) { return {a.v + b.v, a.g + b.g, a.h + b.h}; }
Jet operator*(double s, const Jet& a) { return {s * a.v, s * a.g, s * a.h}; }
Jet operator*(const Jet& a, const Jet& b) {
  return {a.v * b.v, a.g * b.v + b.g * a.v,
          a.h * b.v + b.h * a.v + a.g * b.g.transpose() + b.g * a.g.transpose()};
}
Jet add(const Jet& a, double s) { return {a.v + s, a.g, a.h}; }
// a^p for a > 0.
Jet power(const Jet& a, double p) {
  const double d1 = p * std::pow(a.v, p - 1.0), d2 = p * (p - 1.0) * std::pow(a.v, p - 2.0);
  return {std::pow(a.v, p), d1 * a.g, d1 * a.h + d2 * a.g * a.g.transpose()};
}

StretchDerivatives mooney_rivlin(const MaterialConstants& m, const Eigen::Vector3d& s) {
  const Jet s1 = variable(s[0], 0), s2 = variable(s[1], 1), s3 = variable(s[2], 2);
  const Jet q1 = s1 * s1, q2 = s2 * s2, q3 = s3 * s3;
  const Jet i1 = q1 + q2 + q3;
  const Jet i2 = q1 * q2 + q2 * q3 + q1 * q3;
  const Jet j = s1 * s2 * s3;
  const Jet dj = add(j, -1.0);
  const Jet psi = m.c10 * add(power(j, -2.0 / 3.0) * i1, -3.0) +
                  m.c01 * add(power(j, -4.0 / 3.0) * i2, -3.0) + (0.5 * m.bulk) * (dj * dj);
  return {psi.v, psi.g, psi.h};
}

StretchDerivatives neo_hookean(const MaterialConstants& m, const Eigen::Vector3d& s) {
  const double j = s[0] * s[1] * s[2], log_j = std::log(j);
  StretchDerivatives d;
  d.energy = 0.5 * m.mu * (s.squaredNorm() - 3.0) - m.mu * log_j + 0.5 * m.lambda * log_j * log_j;
  for (int i = 0; i < 3; ++i) {
    d.gradient[i] = m.mu * s[i] + (m.lambda * log_j - m.mu) / s[i];
    for (int k = 0; k < 3; ++k)
      d.hessian(i, k) = i == k ? m.mu + (m.mu + m.lambda - m.lambda * log_j) / (s[i] * s[i])
                               : m.lambda / (s[i] * s[k]);
  }
  return d;
}

StretchDerivatives st_venant_kirchhoff(const MaterialConstants& m, const Eigen::Vector3d& s) {
  const Eigen::Vector3d e = 0.5 * (s.cwiseProduct(s) - Eigen::Vector3d::Ones());
  const double trace = e.sum();
  StretchDerivatives d;
  d.energy = m.mu * e.squaredNorm() + 0.5 * m.lambda * trace * trace;
  for (int i = 0; i < 3; ++i) {
    const double stress = 2.0 * m.mu * e[i] + m.lambda * trace;  // second Piola-Kirchhoff, Pa
    d.gradient[i] = stress * s[i];
    for (int k = 0; k < 3; ++k)
      d.hessian(i, k) =
          i == k ? (2.0 * m.mu + m.lambda) * s[i] * s[i] + stress : m.lambda * s[i] * s[k];
  }
  return d;
}

}  // namespace

StretchDerivatives stretch_derivatives(const MaterialConstants& material,
                                       const Eigen::Vector3d& sigma) {
  switch (material.law) {
    case MaterialLaw::kStVenantKirchhoff: return st_venant_kirchhoff(material, sigma);
    case MaterialLaw::kMooneyRivlin: return mooney_rivlin(material, sigma);
    case MaterialLaw::kNeoHookean: break;
  }
  return neo_hookean(material, sigma);
}

double lowest_stretch(const MaterialConstants& material) {
  // St Venant-Kirchhoff softens in compression below 1/sqrt(3) (its stress turns back toward
  // zero and it has a second minimum at full inversion): the continuation takes over there.
  return material.law == MaterialLaw::kStVenantKirchhoff
             ? std::max(material.min_stretch, 1.0 / std::sqrt(3.0))
             : material.min_stretch;
}

StretchDerivatives clamped_stretch_derivatives(const MaterialConstants& material,
                                               const Eigen::Vector3d& sigma) {
  const Eigen::Vector3d clamped = sigma.cwiseMax(lowest_stretch(material));
  StretchDerivatives d = stretch_derivatives(material, clamped);
  if (clamped == sigma) return d;
  // The continuation's curvature is the clamped point's Hessian with negative eigenvalues set
  // to zero: the energy keeps rising the further an element is crushed or inverted.
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen;
  eigen.computeDirect(d.hessian);
  d.hessian = eigen.eigenvectors() * eigen.eigenvalues().cwiseMax(0.0).asDiagonal() *
              eigen.eigenvectors().transpose();
  const Eigen::Vector3d offset = sigma - clamped;
  d.energy += d.gradient.dot(offset) + 0.5 * offset.dot(d.hessian * offset);
  d.gradient += d.hessian * offset;
  return d;
}

double clamped_stretch_energy(const MaterialConstants& material, const Eigen::Vector3d& sigma) {
  const Eigen::Vector3d clamped = sigma.cwiseMax(lowest_stretch(material));
  if (clamped != sigma) return clamped_stretch_derivatives(material, sigma).energy;
  if (material.law == MaterialLaw::kNeoHookean) {
    const double log_j = std::log(sigma.prod());
    return 0.5 * material.mu * (sigma.squaredNorm() - 3.0) - material.mu * log_j +
           0.5 * material.lambda * log_j * log_j;
  }
  return stretch_derivatives(material, sigma).energy;
}

}  // namespace tacta::models::hyperelastic
