// The values a model's parameter panel edits, one per schema entry, and the ParamSet they make
// (schema order, as request_model_swap expects). No GUI here, so it is testable on its own.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "tacta/param_defaults.hpp"
#include "tacta/plugin.h"
#include "tacta/scene.hpp"

namespace tacta::view {

struct ParamValue {
  const tacta_param_spec* spec = nullptr;  // lives as long as the plugin registry
  double number = 0;                       // REAL, INT, BOOL (0/1), CHOICE index
  std::string text;                        // TEXT
  std::vector<double> values;              // VECTOR
};

// The schema's defaults, overridden by the entries `current` names (e.g. the scene's values).
std::vector<ParamValue> param_values(std::span<const tacta_param_spec> schema,
                                     const ParamSet* current = nullptr);

// The ParamSet of these values; CHOICE entries carry their choice name and index.
ParamSet to_param_set(const std::vector<ParamValue>& values);

// choice_names() and parse_numbers(): tacta/param_defaults.hpp.
using tacta::choice_names;
using tacta::parse_numbers;

}  // namespace tacta::view
