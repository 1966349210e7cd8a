// Plugin references in a scene ("name" or {name: x, <param>: value, ...}) and their parameters,
// validated against the plugin's schema and filled in schema order, defaults included.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "scene/yaml_field.hpp"
#include "tacta/plugin.h"
#include "tacta/scene.hpp"

namespace tacta::scene_detail {

struct PluginRef {
  std::string name;
  ParamSet params;
};

// Reads `field` as a plugin of `kind`. `extra_params` is an optional sibling map of parameters
// (a device's `params:`). With `must_exist` false an unknown plugin name is accepted as is, with
// no parameters (a disabled collision pipeline); a known one is still checked.
PluginRef read_plugin(const Field& field, tacta_kind kind,
                      const std::optional<Field>& extra_params = std::nullopt,
                      bool must_exist = true);

// Validates `given` (key field, value field) against `schema` and returns every parameter in
// schema order; `owner` names the plugin in messages.
ParamSet resolve_params(std::span<const tacta_param_spec> schema,
                        const std::vector<std::pair<Field, Field>>& given,
                        const std::string& plugin_name);

}  // namespace tacta::scene_detail
