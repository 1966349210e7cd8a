#include "param_defaults.hpp"

#include <sstream>
#include <string>

namespace tacta {

namespace {

// The name of choice `index` in "a|b|c".
std::string choice_name(const char* choices, int index) {
  std::string all = choices ? choices : "";
  for (int i = 0; i < index; ++i) {
    const size_t bar = all.find('|');
    if (bar == std::string::npos) return {};
    all.erase(0, bar + 1);
  }
  return all.substr(0, all.find('|'));
}

}  // namespace

ParamSet complete_params(const tacta_descriptor& descriptor, const ParamSet& given) {
  if (given.size() == descriptor.param_count) return given;
  ParamSet defaults;
  for (uint32_t i = 0; i < descriptor.param_count; ++i) {
    const tacta_param_spec& p = descriptor.params[i];
    switch (p.type) {
      case TACTA_PARAM_CHOICE:
        defaults.add_text(p.name, choice_name(p.choices, static_cast<int>(p.default_value)), p.default_value);
        break;
      case TACTA_PARAM_TEXT: defaults.add_text(p.name, p.default_text ? p.default_text : ""); break;
      case TACTA_PARAM_VECTOR: {
        std::vector<double> values;
        std::istringstream in(p.default_text ? p.default_text : "");
        for (double v; in >> v;) values.push_back(v);
        defaults.add_vector(p.name, std::move(values));
        break;
      }
      default: defaults.add_number(p.name, p.default_value); break;
    }
  }
  return defaults;
}

}  // namespace tacta
