// "Did you mean": Levenshtein distance between a mistyped name and the known ones.
#include <algorithm>
#include <numeric>

#include "tacta/plugin_registry.hpp"

namespace tacta {

namespace {

// Insertions, deletions and substitutions, each costing 1; two rolling rows.
size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<size_t> previous(b.size() + 1), current(b.size() + 1);
  std::iota(previous.begin(), previous.end(), size_t{0});
  for (size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t substitute = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitute});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

}  // namespace

std::vector<std::string> closest_names(std::string_view name,
                                       const std::vector<std::string>& candidates) {
  std::vector<std::pair<size_t, std::string>> scored;
  for (const std::string& c : candidates) {
    const size_t d = edit_distance(name, c);
    // A typo changes a few characters: allow 2, or a third of the longer name if that is more.
    const size_t limit = std::max<size_t>(2, std::max(name.size(), c.size()) / 3);
    if (d > 0 && d <= limit) scored.emplace_back(d, c);
  }
  std::sort(scored.begin(), scored.end());
  std::vector<std::string> names;
  for (auto& [distance, candidate] : scored) names.push_back(std::move(candidate));
  return names;
}

}  // namespace tacta
