#include "param_values.hpp"

#include "tacta/param_defaults.hpp"

namespace tacta::view {

std::vector<ParamValue> param_values(std::span<const tacta_param_spec> schema,
                                     const ParamSet* current) {
  const ParamSet defaults = defaults_of(schema);
  std::vector<ParamValue> out;
  for (size_t i = 0; i < schema.size(); ++i) {
    const tacta_param_spec& spec = schema[i];
    const tacta_param_value* given = current != nullptr ? current->find(spec.name) : nullptr;
    if (given == nullptr) given = &defaults.data()[i];
    ParamValue v;
    v.spec = &spec;
    v.number = given->number;
    if (spec.type == TACTA_PARAM_TEXT && given->text != nullptr) v.text = given->text;
    if (spec.type == TACTA_PARAM_VECTOR && given->values != nullptr)
      v.values.assign(given->values, given->values + given->count);
    out.push_back(std::move(v));
  }
  return out;
}

ParamSet to_param_set(const std::vector<ParamValue>& values) {
  ParamSet set;
  for (const ParamValue& v : values) {
    const tacta_param_spec& spec = *v.spec;
    switch (spec.type) {
      case TACTA_PARAM_CHOICE:
        set.add_text(spec.name, choice_name(spec, static_cast<size_t>(v.number)), v.number);
        break;
      case TACTA_PARAM_TEXT: set.add_text(spec.name, v.text); break;
      case TACTA_PARAM_VECTOR: set.add_vector(spec.name, v.values); break;
      default: set.add_number(spec.name, v.number); break;
    }
  }
  return set;
}

}  // namespace tacta::view
