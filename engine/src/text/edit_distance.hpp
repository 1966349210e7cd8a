// How far a mistyped name is from a known one, for every "did you mean" hint the engine gives
// (scene keys and choices, plugin names).
#pragma once

#include <string_view>

namespace tacta {

// Optimal string alignment distance (Levenshtein plus adjacent transpositions), case-insensitive.
size_t edit_distance(std::string_view a, std::string_view b);

}  // namespace tacta
