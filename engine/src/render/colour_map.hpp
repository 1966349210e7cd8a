// A perceptually ordered colour map (dark blue-violet to yellow), for scalar fields on bodies.
#pragma once

#include "tacta/render/frame.hpp"

namespace tacta::render::detail {

// t in [0, 1] (clamped; NaN gives the low end) to a display colour.
Rgb colour_map(double t);

// Maps value over [low, high] to [0, 1]; a zero or negative span maps everything to 0.
double normalise_scalar(double value, double low, double high);

}  // namespace tacta::render::detail
