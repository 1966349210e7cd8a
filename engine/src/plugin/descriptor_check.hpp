// Validation of one descriptor as a plugin registers it: sizes, ABI id, kind, name, parameter
// schema and the function table's required entries. Returns the reason it is refused, if any.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "tacta/plugin.h"

namespace tacta::plugin {

// The required/optional table of a kind's api struct; empty for an unknown kind.
std::span<const tacta_api_field> api_fields(tacta_kind kind);

// nullopt when the descriptor is acceptable; otherwise one line saying what is wrong.
std::optional<std::string> check_descriptor(const tacta_descriptor* descriptor, uint64_t host_abi);

// One parameter spec; nullopt when sane.
std::optional<std::string> check_param(const tacta_param_spec& spec);

}  // namespace tacta::plugin
