// A plugin's schema defaults as the values the engine passes when a scene sets none, and the two
// schema fields that need parsing (CHOICE names, VECTOR defaults). Header-only: the engine, the
// apps, plugins and tests all fill defaults through defaults_of().
#pragma once

#include <cstddef>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "tacta/param_set.hpp"
#include "tacta/plugin.h"

namespace tacta {

// The names in a schema list "a|b|c" (CHOICE choices, a model's live parameters); empty for NULL.
inline std::vector<std::string> bar_list(const char* list) {
  std::vector<std::string> names;
  if (list == nullptr) return names;
  const std::string all(list);
  size_t start = 0;
  for (size_t bar = all.find('|'); bar != std::string::npos; bar = all.find('|', start)) {
    names.push_back(all.substr(start, bar - start));
    start = bar + 1;
  }
  names.push_back(all.substr(start));
  return names;
}

// The names of a CHOICE parameter ("a|b|c" -> a, b, c); empty when it has no choices.
inline std::vector<std::string> choice_names(const tacta_param_spec& spec) {
  return bar_list(spec.choices);
}

// The schema index of parameter `name`, or param_count when the descriptor has none.
inline uint32_t param_index(const tacta_descriptor& d, std::string_view name) {
  uint32_t index = 0;
  while (index < d.param_count && name != d.params[index].name) ++index;
  return index;
}

// The name of choice `index`, or "" when there is no such choice.
inline std::string choice_name(const tacta_param_spec& spec, size_t index) {
  const std::vector<std::string> names = choice_names(spec);
  return index < names.size() ? names[index] : std::string();
}

// Whitespace-separated numbers ("0 0 1"), as VECTOR defaults are written; stops at the first
// token that is not a number (the descriptor check rejects such defaults at load).
inline std::vector<double> parse_numbers(const char* text) {
  std::vector<double> out;
  if (text == nullptr) return out;
  std::istringstream in(text);
  for (double v = 0; in >> v;) out.push_back(v);
  return out;
}

// One parameter's default, appended to `set`: REAL/INT/BOOL as the number; CHOICE as the chosen
// name with its index as the number; TEXT as the text ("" when none); VECTOR as its numbers.
inline void add_default(ParamSet& set, const tacta_param_spec& spec) {
  switch (spec.type) {
    case TACTA_PARAM_CHOICE:
      set.add_text(spec.name, choice_name(spec, static_cast<size_t>(spec.default_value)),
                   spec.default_value);
      return;
    case TACTA_PARAM_TEXT:
      set.add_text(spec.name, spec.default_text ? spec.default_text : "");
      return;
    case TACTA_PARAM_VECTOR: set.add_vector(spec.name, parse_numbers(spec.default_text)); return;
    default: set.add_number(spec.name, spec.default_value); return;
  }
}

// Every parameter of the schema at its default, in schema order.
inline ParamSet defaults_of(std::span<const tacta_param_spec> schema) {
  ParamSet set;
  for (const tacta_param_spec& spec : schema) add_default(set, spec);
  return set;
}
inline ParamSet defaults_of(const tacta_descriptor& descriptor) {
  return defaults_of(std::span<const tacta_param_spec>(descriptor.params, descriptor.param_count));
}

}  // namespace tacta
