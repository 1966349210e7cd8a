// Typo hints for scene messages (the distance: text/edit_distance.hpp).
#include "scene/did_you_mean.hpp"

#include <algorithm>

namespace tacta::scene_detail {

std::optional<std::string> closest_match(std::string_view word,
                                         const std::vector<std::string>& candidates) {
  // A typo budget that grows with the word: 2 edits for short words, a third of longer ones.
  const size_t budget = std::max<size_t>(2, word.size() / 3);
  std::optional<std::string> best;
  size_t best_distance = budget + 1;
  for (const std::string& candidate : candidates) {
    const size_t d = edit_distance(word, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

std::string join(const std::vector<std::string>& words, std::string_view separator) {
  std::string out;
  for (size_t i = 0; i < words.size(); ++i) {
    if (i) out += separator;
    out += words[i];
  }
  return out;
}

std::string unknown_name_message(std::string_view noun, std::string_view word,
                                 const std::vector<std::string>& candidates) {
  std::string message = "unknown " + std::string(noun) + " '" + std::string(word) + "'";
  if (auto hint = closest_match(word, candidates)) message += "; did you mean '" + *hint + "'?";
  if (candidates.empty())
    message += " (none is allowed here)";
  else
    message += " (expected one of: " + join(candidates) + ")";
  return message;
}

}  // namespace tacta::scene_detail
