// "did you mean 'X'?" hints for unknown keys, plugin names, parameters and choices.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "text/edit_distance.hpp"

namespace tacta::scene_detail {

using tacta::edit_distance;

// The candidate closest to `word` if it is close enough to be a likely typo.
std::optional<std::string> closest_match(std::string_view word,
                                         const std::vector<std::string>& candidates);

// "unknown <noun> 'word'; did you mean 'x'? (expected one of: a, b, c)"; the hint is left out
// when nothing is close, the list when there are no candidates.
std::string unknown_name_message(std::string_view noun, std::string_view word,
                                 const std::vector<std::string>& candidates);

// "a, b, c"
std::string join(const std::vector<std::string>& words, std::string_view separator = ", ");

}  // namespace tacta::scene_detail
