// Edit distance and typo hints for scene messages.
#include "scene/did_you_mean.hpp"

#include <algorithm>
#include <cctype>

namespace tacta::scene_detail {

namespace {
char lower(char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); }
}  // namespace

size_t edit_distance(std::string_view a, std::string_view b) {
  const size_t n = a.size(), m = b.size();
  // Three rows suffice for the transposition rule: previous-previous, previous, current.
  std::vector<size_t> before(m + 1), previous(m + 1), current(m + 1);
  for (size_t j = 0; j <= m; ++j) previous[j] = j;
  for (size_t i = 1; i <= n; ++i) {
    current[0] = i;
    for (size_t j = 1; j <= m; ++j) {
      const size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
          lower(a[i - 2]) == lower(b[j - 1]))
        current[j] = std::min(current[j], before[j - 2] + 1);
    }
    before.swap(previous);
    previous.swap(current);
  }
  return previous[m];
}

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
