// Conversions between the engineering constants (Young's modulus E, Poisson's ratio nu) and the
// Lamé coefficients (lambda, mu) of an isotropic linear material: the one copy the engine, the
// plugins and the conformance bodies use. Units: Pa for moduli.
#pragma once

namespace tacta::sdk {

struct Lame {
  double lambda = 0;  // Pa
  double mu = 0;      // Pa, the shear modulus
};

// lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).
constexpr Lame lame_from_young(double youngs_modulus, double poisson_ratio) noexcept {
  const double e = youngs_modulus, nu = poisson_ratio;
  return {e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))};
}

// E = mu (3 lambda + 2 mu) / (lambda + mu).
constexpr double young_from_lame(double lambda, double mu) noexcept {
  return mu * (3 * lambda + 2 * mu) / (lambda + mu);
}

// nu = lambda / (2 (lambda + mu)).
constexpr double poisson_from_lame(double lambda, double mu) noexcept {
  return lambda / (2 * (lambda + mu));
}

}  // namespace tacta::sdk
