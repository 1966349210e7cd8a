// Which of a model's parameters are live: changed by its set_param between steps, without a swap
// to a fresh instance (tacta_model_api.live_params). Shared by the loader's descriptor check, the
// stepping API, `tacta plugins` and `tacta check-plugin`.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "tacta/model_api.h"
#include "tacta/param_defaults.hpp"
#include "tacta/plugin.h"

namespace tacta {

// The names in the descriptor's live list, in its order; empty for other kinds or no list.
inline std::vector<std::string> live_param_names(const tacta_descriptor& d) {
  if (d.kind != TACTA_KIND_MODEL || d.api == nullptr) return {};
  const char* list =
      tacta_model_live_params(static_cast<const tacta_model_api*>(d.api), d.api_size);
  if (list == nullptr || list[0] == '\0') return {};
  return bar_list(list);
}

inline bool is_live_param(const tacta_descriptor& d, std::string_view name) {
  for (const std::string& live : live_param_names(d))
    if (live == name) return true;
  return false;
}

}  // namespace tacta
