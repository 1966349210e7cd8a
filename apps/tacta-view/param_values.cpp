#include "param_values.hpp"

#include <cstdlib>
#include <sstream>

namespace tacta::view {

std::vector<std::string> choice_names(const tacta_param_spec& spec) {
  std::vector<std::string> names;
  if (spec.choices == nullptr) return names;
  std::string all(spec.choices);
  size_t start = 0;
  for (size_t bar = all.find('|'); bar != std::string::npos; bar = all.find('|', start)) {
    names.push_back(all.substr(start, bar - start));
    start = bar + 1;
  }
  names.push_back(all.substr(start));
  return names;
}

std::vector<double> parse_numbers(const char* text) {
  std::vector<double> out;
  if (text == nullptr) return out;
  std::istringstream in(text);
  for (double v = 0; in >> v;) out.push_back(v);
  return out;
}

std::vector<ParamValue> param_values(std::span<const tacta_param_spec> schema, const ParamSet* current) {
  std::vector<ParamValue> out;
  for (const tacta_param_spec& spec : schema) {
    ParamValue v;
    v.spec = &spec;
    v.number = spec.default_value;
    if (spec.type == TACTA_PARAM_TEXT && spec.default_text != nullptr) v.text = spec.default_text;
    if (spec.type == TACTA_PARAM_VECTOR) v.values = parse_numbers(spec.default_text);
    const tacta_param_value* given = current != nullptr ? current->find(spec.name) : nullptr;
    if (given != nullptr) {
      v.number = given->number;
      if (spec.type == TACTA_PARAM_TEXT && given->text != nullptr) v.text = given->text;
      if (spec.type == TACTA_PARAM_VECTOR && given->values != nullptr)
        v.values.assign(given->values, given->values + given->count);
    }
    out.push_back(std::move(v));
  }
  return out;
}

ParamSet to_param_set(const std::vector<ParamValue>& values) {
  ParamSet set;
  for (const ParamValue& v : values) {
    const tacta_param_spec& spec = *v.spec;
    switch (spec.type) {
      case TACTA_PARAM_CHOICE: {
        const std::vector<std::string> names = choice_names(spec);
        const auto index = static_cast<size_t>(v.number);
        set.add_text(spec.name, index < names.size() ? names[index] : std::string(), v.number);
        break;
      }
      case TACTA_PARAM_TEXT: set.add_text(spec.name, v.text); break;
      case TACTA_PARAM_VECTOR: set.add_vector(spec.name, v.values); break;
      default: set.add_number(spec.name, v.number); break;
    }
  }
  return set;
}

}  // namespace tacta::view
