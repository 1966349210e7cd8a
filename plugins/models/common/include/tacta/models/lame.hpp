// Conversions between (E, nu) and the Lamé coefficients, and the elastic wave speeds they give.
// Units: Pa for moduli, kg/m^3 for density, m/s for speeds.
#pragma once

#include <cmath>

namespace tacta::models {

struct Lame {
  double lambda = 0;  // Pa
  double mu = 0;      // Pa (shear modulus)
};

inline Lame lame_from_young(double youngs_modulus, double poisson_ratio) {
  const double e = youngs_modulus, nu = poisson_ratio;
  return {e * nu / ((1 + nu) * (1 - 2 * nu)), e / (2 * (1 + nu))};
}

inline double young_from_lame(double lambda, double mu) {
  return mu * (3 * lambda + 2 * mu) / (lambda + mu);
}

inline double poisson_from_lame(double lambda, double mu) { return lambda / (2 * (lambda + mu)); }

// Pressure (longitudinal) wave speed in an unbounded solid, m/s.
inline double p_wave_speed(double lambda, double mu, double density) {
  return std::sqrt((lambda + 2 * mu) / density);
}

// Shear (transverse) wave speed, m/s.
inline double s_wave_speed(double mu, double density) { return std::sqrt(mu / density); }

}  // namespace tacta::models
