// Parameter values for a plugin when a caller gives none: the schema's defaults, in schema order.
#pragma once

#include "tacta/param_defaults.hpp"
#include "tacta/plugin.h"
#include "tacta/scene.hpp"

namespace tacta {

// `given` when it already holds every schema value, else the defaults (a partial set is a
// programming error upstream: the scene loader always fills every value).
inline ParamSet complete_params(const tacta_descriptor& descriptor, const ParamSet& given) {
  return given.size() == descriptor.param_count ? given : defaults_of(descriptor);
}

}  // namespace tacta
