// Validation of plugin parameters against their schema (plugin.h: tacta_param_spec).
#include "scene/plugin_params.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "scene/did_you_mean.hpp"
#include "tacta/param_defaults.hpp"
#include "tacta/scene_loader.hpp"

namespace tacta::scene_detail {

namespace {

int64_t clamp_to_int64(double x) {
  if (!(x > -9.0e18)) return -9'000'000'000'000'000'000LL;
  if (!(x < 9.0e18)) return 9'000'000'000'000'000'000LL;
  return static_cast<int64_t>(x);
}

void add_given(ParamSet& set, const tacta_param_spec& spec, const Field& value) {
  const Range range = Range::closed(spec.min_value, spec.max_value);
  switch (spec.type) {
    case TACTA_PARAM_REAL: set.add_number(spec.name, value.real(range)); return;
    case TACTA_PARAM_INT:
      set.add_number(spec.name, static_cast<double>(
                                    value.integer(clamp_to_int64(std::ceil(spec.min_value)),
                                                  clamp_to_int64(std::floor(spec.max_value)))));
      return;
    case TACTA_PARAM_BOOL: set.add_number(spec.name, value.boolean() ? 1.0 : 0.0); return;
    case TACTA_PARAM_CHOICE: {
      const std::vector<std::string> choices = choice_names(spec);
      const std::string chosen = value.choice(choices);
      for (size_t i = 0; i < choices.size(); ++i)
        if (choices[i] == chosen) set.add_text(spec.name, chosen, static_cast<double>(i));
      return;
    }
    case TACTA_PARAM_TEXT: {
      // TEXT values are file paths unless the plugin marks them as plain text with unit "text".
      const bool plain = spec.unit != nullptr && std::string(spec.unit) == "text";
      set.add_text(spec.name, plain ? value.text() : value.file_path());
      return;
    }
    case TACTA_PARAM_VECTOR: {
      std::vector<double> values = value.reals(0, range);
      const uint32_t stride = spec.vector_stride == 0 ? 1 : spec.vector_stride;
      if (values.size() % stride != 0)
        value.fail_expected("a list whose length is a multiple of " + std::to_string(stride));
      set.add_vector(spec.name, std::move(values));
      return;
    }
    default:
      value.fail("the plugin declares an unknown type for parameter '" + std::string(spec.name) +
                 "'");
  }
}

}  // namespace

ParamSet resolve_params(std::span<const tacta_param_spec> schema,
                        const std::vector<std::pair<Field, Field>>& given,
                        const std::string& plugin_name) {
  std::vector<std::string> known;
  for (const tacta_param_spec& spec : schema) known.emplace_back(spec.name);
  for (const auto& [key, value] : given) {
    const std::string name = key.yaml().Scalar();
    if (std::find(known.begin(), known.end(), name) != known.end()) continue;
    std::string message = "unknown parameter '" + name + "' for plugin '" + plugin_name + "'";
    if (auto hint = closest_match(name, known)) message += "; did you mean '" + *hint + "'?";
    message +=
        known.empty() ? " (it takes no parameters)" : " (its parameters: " + join(known) + ")";
    key.fail(message);
  }
  ParamSet set;
  for (const tacta_param_spec& spec : schema) {
    const Field* value = nullptr;
    for (const auto& [key, candidate] : given)
      if (key.yaml().Scalar() == spec.name) value = &candidate;
    if (value)
      add_given(set, spec, *value);
    else
      add_default(set, spec);
  }
  return set;
}

PluginRef read_plugin(const Field& field, tacta_kind kind, const std::optional<Field>& extra_params,
                      bool must_exist) {
  const std::string noun = std::string(tacta_kind_name(kind)) + " plugin";
  PluginRef ref;
  std::vector<std::pair<Field, Field>> given;
  std::optional<Field> name_field;
  if (field.is_map()) {
    name_field = field.require("name");
    std::vector<std::string> seen;
    for (const auto& [key_name, key] : field.keys()) {
      if (std::find(seen.begin(), seen.end(), key_name) != seen.end())
        key.fail("duplicate key '" + key_name + "'");
      seen.push_back(key_name);
      if (key_name != "name") given.emplace_back(key, *field.get(key_name));
    }
  } else if (field.is_scalar()) {
    name_field = field;
  } else {
    field.fail_expected("a " + noun +
                        " name, or a map {name: <plugin>, <parameter>: <value>, ...}");
  }
  ref.name = name_field->text();
  if (extra_params) {
    for (const auto& [key_name, key] : extra_params->keys()) {
      for (const auto& [earlier, unused] : given)
        if (earlier.yaml().Scalar() == key_name)
          key.fail("parameter '" + key_name + "' is given twice (also at " + earlier.path() + ")");
      given.emplace_back(key, *extra_params->get(key_name));
    }
  }
  const SchemaLookup& lookup = *field.context().schemas;
  const auto schema = lookup.schema(kind, ref.name);
  if (!schema) {
    if (!must_exist) return ref;
    const std::vector<std::string> available = lookup.names(kind);
    std::string message = "unknown " + noun + " '" + ref.name + "'";
    if (auto hint = closest_match(ref.name, available))
      message += "; did you mean '" + *hint + "'?";
    message += available.empty() ? " (no " + noun + "s are available)"
                                 : " (available: " + join(available) + ")";
    name_field->fail(message);
  }
  ref.params = resolve_params(*schema, given, ref.name);
  return ref;
}

}  // namespace tacta::scene_detail
