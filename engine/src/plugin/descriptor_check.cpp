// Descriptor validation: everything the engine later relies on without checking again.
#include "plugin/descriptor_check.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string_view>
#include <vector>

#include "tacta/device_api.h"
#include "tacta/live_params.hpp"
#include "tacta/model_api.h"
#include "tacta/param_defaults.hpp"
#if __has_include("tacta/collision_api.h")
#include "tacta/collision_api.h"
#define TACTA_HAVE_COLLISION_FIELDS 1
#endif

namespace tacta::plugin {

std::span<const tacta_api_field> api_fields(tacta_kind kind) {
  switch (kind) {
    case TACTA_KIND_MODEL: return tacta_model_api_fields;
    case TACTA_KIND_DEVICE: return tacta_device_api_fields;
#ifdef TACTA_HAVE_COLLISION_FIELDS
    case TACTA_KIND_COLLISION: return tacta_collision_api_fields;
#endif
    default: return {};
  }
}

namespace {

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::optional<std::string> check_range(const tacta_param_spec& spec, bool check_default) {
  if (std::isnan(spec.min_value) || std::isnan(spec.max_value) || spec.min_value > spec.max_value)
    return "range [" + number(spec.min_value) + ", " + number(spec.max_value) +
           "] is empty (min must be <= max)";
  if (check_default &&
      !(spec.default_value >= spec.min_value && spec.default_value <= spec.max_value))
    return "default " + number(spec.default_value) + " is outside [" + number(spec.min_value) +
           ", " + number(spec.max_value) + "]";
  return std::nullopt;
}

// VECTOR defaults are space-separated numbers: a multiple of the stride, each within range.
std::optional<std::string> check_vector_default(const tacta_param_spec& spec) {
  if (spec.default_text == nullptr) return std::nullopt;
  const char* cursor = spec.default_text;
  size_t count = 0;
  for (;;) {
    char* end = nullptr;
    const double value = std::strtod(cursor, &end);
    if (end == cursor) break;
    if (!(value >= spec.min_value && value <= spec.max_value))
      return "default element " + number(value) + " is outside the range";
    ++count;
    cursor = end;
  }
  while (*cursor == ' ' || *cursor == ',') ++cursor;
  if (*cursor != '\0')
    return std::string("default '") + spec.default_text + "' is not a list of numbers";
  if (count % spec.vector_stride != 0)
    return "default has " + std::to_string(count) + " numbers, not a multiple of the stride " +
           std::to_string(spec.vector_stride);
  return std::nullopt;
}

std::optional<std::string> check_api(const tacta_descriptor& d) {
  if (d.api == nullptr) return std::string("function table (api) is NULL");
  const std::span<const tacta_api_field> fields = api_fields(d.kind);
  if (fields.empty()) return std::nullopt;  // kind known but its table is not described yet
  // The table must reach past the last required entry; optional ones beyond api_size are absent.
  size_t needed = 0;
  for (const tacta_api_field& f : fields)
    if (f.required && f.offset + sizeof(void*) > needed) needed = f.offset + sizeof(void*);
  if (d.api_size < needed)
    return "function table is " + std::to_string(d.api_size) + " bytes, needs at least " +
           std::to_string(needed) + " for its required entries";
  const auto* bytes = static_cast<const unsigned char*>(d.api);
  for (const tacta_api_field& f : fields) {
    if (!f.required) continue;
    void (*entry)(void) = nullptr;
    std::memcpy(&entry, bytes + f.offset, sizeof entry);  // read a function pointer, no aliasing
    if (entry == nullptr)
      return std::string("required function '") + f.name + "' is missing (NULL) in its " +
             tacta_kind_name(d.kind) + " function table";
  }
  return std::nullopt;
}

// A live list names parameters of the schema that set_param can take: numbers, and an entry.
std::optional<std::string> check_live_params(const tacta_descriptor& d) {
  const std::vector<std::string> live = live_param_names(d);
  if (live.empty()) return std::nullopt;
  if (static_cast<const tacta_model_api*>(d.api)->set_param == nullptr)
    return std::string("live_params lists parameters but set_param is NULL");
  for (const std::string& name : live) {
    const uint32_t index = param_index(d, name);
    if (index == d.param_count) return "live_params names '" + name + "', which is not a parameter";
    const tacta_param_spec* spec = &d.params[index];
    if (spec->type != TACTA_PARAM_REAL && spec->type != TACTA_PARAM_INT &&
        spec->type != TACTA_PARAM_BOOL)
      return "live parameter '" + name + "' is not a number (REAL, INT or BOOL)";
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> check_param(const tacta_param_spec& spec) {
  switch (spec.type) {
    case TACTA_PARAM_REAL:
    case TACTA_PARAM_INT: return check_range(spec, true);
    case TACTA_PARAM_BOOL:
      if (spec.default_value != 0.0 && spec.default_value != 1.0)
        return "BOOL default must be 0 or 1, not " + number(spec.default_value);
      return std::nullopt;
    case TACTA_PARAM_CHOICE: {
      if (spec.choices == nullptr || spec.choices[0] == '\0')
        return std::string("CHOICE has no choices");
      const size_t n = choice_names(spec).size();
      if (!(spec.default_value >= 0 && spec.default_value < static_cast<double>(n)))
        return "CHOICE default index " + number(spec.default_value) + " is not one of the " +
               std::to_string(n) + " choices '" + spec.choices + "'";
      return std::nullopt;
    }
    case TACTA_PARAM_TEXT: return std::nullopt;
    case TACTA_PARAM_VECTOR:
      if (spec.vector_stride == 0) return std::string("VECTOR stride is 0");
      if (auto bad = check_range(spec, false)) return bad;
      return check_vector_default(spec);
    default: return "unknown parameter type " + std::to_string(spec.type);
  }
}

std::optional<std::string> check_descriptor(const tacta_descriptor* d, uint64_t host_abi) {
  if (d == nullptr) return std::string("registered a NULL descriptor");
  if (d->struct_size < sizeof(tacta_descriptor))
    return "descriptor struct_size " + std::to_string(d->struct_size) + " is smaller than " +
           std::to_string(sizeof(tacta_descriptor)) + " (built against an incompatible plugin.h)";
  const std::string who = d->name ? std::string(" '") + d->name + "'" : std::string();
  char abi_message[256] = {0};
  if (!tacta_abi_check(host_abi, d->abi, abi_message, sizeof abi_message))
    return "descriptor" + who + ": ABI refused: " + abi_message;
  if (d->kind != TACTA_KIND_MODEL && d->kind != TACTA_KIND_COLLISION &&
      d->kind != TACTA_KIND_DEVICE)
    return "descriptor" + who + ": unknown kind " + std::to_string(d->kind);
  const std::string label = std::string(tacta_kind_name(d->kind)) + who;
  if (d->name == nullptr || d->name[0] == '\0') return label + ": empty name";
  if (d->param_count > 0 && d->params == nullptr)
    return label + ": " + std::to_string(d->param_count) + " parameters but params is NULL";
  std::set<std::string_view> names;
  for (uint32_t i = 0; i < d->param_count; ++i) {
    const tacta_param_spec& spec = d->params[i];
    if (spec.name == nullptr || spec.name[0] == '\0')
      return label + ": parameter " + std::to_string(i) + " has no name";
    if (!names.insert(spec.name).second)
      return label + ": parameter '" + spec.name + "' is declared twice";
    if (auto bad = check_param(spec)) return label + ": parameter '" + spec.name + "': " + *bad;
  }
  if (auto bad = check_api(*d)) return label + ": " + *bad;
  if (auto bad = check_live_params(*d)) return label + ": " + *bad;
  return std::nullopt;
}

}  // namespace tacta::plugin
