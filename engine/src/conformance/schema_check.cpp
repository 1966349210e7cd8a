// Schema check: beyond what the loader refuses outright (plugin/descriptor_check.cpp), what the
// viewer, the docs and `tacta plugins` rely on: snake_case names, a unit string, help text,
// finite limits, whole-number INT values and no empty CHOICE name.
#include <cmath>
#include <string>

#include "conformance/checks.hpp"
#include "plugin/descriptor_check.hpp"

namespace tacta::conformance {

namespace {

bool snake_case(const char* name) {
  if (name == nullptr || !(name[0] >= 'a' && name[0] <= 'z')) return false;
  for (const char* c = name; *c; ++c)
    if (!((*c >= 'a' && *c <= 'z') || (*c >= '0' && *c <= '9') || *c == '_')) return false;
  return true;
}

bool whole(double v) { return std::isfinite(v) && v == std::floor(v); }

// What is wrong with one parameter, or empty.
std::string problem(const tacta_param_spec& p) {
  if (!snake_case(p.name)) return "name is not snake_case";
  if (auto bad = plugin::check_param(p)) return *bad;
  if (p.unit == nullptr) return "unit is NULL (use \"\" when dimensionless)";
  if (p.help == nullptr || p.help[0] == '\0') return "no help text";
  const bool ranged =
      p.type == TACTA_PARAM_REAL || p.type == TACTA_PARAM_INT || p.type == TACTA_PARAM_VECTOR;
  if (ranged && (std::isnan(p.min_value) || std::isnan(p.max_value))) return "range limit is NaN";
  if (p.type == TACTA_PARAM_REAL && !std::isfinite(p.default_value)) return "default is not finite";
  if (p.type == TACTA_PARAM_INT &&
      !(whole(p.default_value) && whole(p.min_value) && whole(p.max_value)))
    return "INT default or limit is not a whole number";
  if (p.type == TACTA_PARAM_CHOICE) {
    const std::string all = std::string("|") + p.choices + "|";
    if (all.find("||") != std::string::npos)
      return std::string("empty name in choices '") + p.choices + "'";
    if (!whole(p.default_value)) return "CHOICE default index is not a whole number";
  }
  if (p.type == TACTA_PARAM_TEXT && p.default_text == nullptr) return "TEXT default is NULL";
  return {};
}

}  // namespace

CheckResult check_schema(const tacta_descriptor& model) {
  const char* name = "parameter schema";
  if (model.param_count > 0 && model.params == nullptr)
    return {name, "param_count " + std::to_string(model.param_count) + " but params is NULL",
            Verdict::Fail};
  for (uint32_t i = 0; i < model.param_count; ++i) {
    const tacta_param_spec& p = model.params[i];
    const std::string bad = problem(p);
    if (!bad.empty())
      return {name, "parameter " + std::to_string(i) + " '" + (p.name ? p.name : "") + "': " + bad,
              Verdict::Fail};
  }
  return {name,
          std::to_string(model.param_count) +
              " parameters: names, units, help, ranges and defaults sane",
          Verdict::Pass};
}

}  // namespace tacta::conformance
