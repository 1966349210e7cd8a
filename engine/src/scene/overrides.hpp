// --set overrides: "key.path=value" strings applied to the scene's YAML tree before validation.
#pragma once

#include <string>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "scene/yaml_field.hpp"

namespace tacta::scene_detail {

// Applies each override in order. Path segments are map keys, list indices ("bodies.0"), a list
// element's `name` ("bodies.liver") or "*" (every element). Missing map keys are created; the
// value is parsed as YAML. Records the concrete paths written in `origins` so later errors point
// at the override. A malformed override throws InputError located at "--set <override>".
void apply_overrides(YAML::Node& root, const std::vector<std::string>& overrides,
                     std::vector<OverrideOrigin>& origins);

}  // namespace tacta::scene_detail
