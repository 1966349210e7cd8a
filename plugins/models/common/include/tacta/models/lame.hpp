// The Lamé conversions (tacta/sdk/elastic_constants.hpp) and the elastic wave speeds they give.
// Units: Pa for moduli, kg/m^3 for density, m/s for speeds.
#pragma once

#include <cmath>

#include "tacta/sdk/elastic_constants.hpp"

namespace tacta::models {

using sdk::Lame;
using sdk::lame_from_young;
using sdk::poisson_from_lame;
using sdk::young_from_lame;

// Pressure (longitudinal) wave speed in an unbounded solid, m/s.
inline double p_wave_speed(double lambda, double mu, double density) {
  return std::sqrt((lambda + 2 * mu) / density);
}

// Shear (transverse) wave speed, m/s.
inline double s_wave_speed(double mu, double density) { return std::sqrt(mu / density); }

}  // namespace tacta::models
