// "Did you mean": the known plugin names a mistyped one is a few edits from.
#include <algorithm>

#include "tacta/plugin_registry.hpp"
#include "text/edit_distance.hpp"

namespace tacta {

std::vector<std::string> closest_names(std::string_view name,
                                       const std::vector<std::string>& candidates) {
  std::vector<std::pair<size_t, std::string>> scored;
  for (const std::string& c : candidates) {
    const size_t d = edit_distance(name, c);
    // A typo changes a few characters: allow 2, or a third of the longer name if that is more.
    const size_t limit = std::max<size_t>(2, std::max(name.size(), c.size()) / 3);
    if (c != name && d <= limit) scored.emplace_back(d, c);
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> names;
  for (auto& [distance, candidate] : scored) names.push_back(std::move(candidate));
  return names;
}

}  // namespace tacta
