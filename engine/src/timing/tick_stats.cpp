// Percentiles of recorded tick durations (nearest-rank on a sorted copy).
#include "tacta/sim/tick_stats.hpp"

#include <algorithm>
#include <cmath>

namespace tacta {

namespace {
double nearest_rank(const std::vector<float>& sorted, double fraction) {
  if (sorted.empty()) return 0;
  const auto rank = static_cast<size_t>(std::ceil(fraction * static_cast<double>(sorted.size())));
  return sorted[std::min(sorted.size(), std::max<size_t>(rank, 1)) - 1];
}
}  // namespace

TickSummary TickRecorder::summary() const {
  TickSummary s;
  s.ticks = count_;
  if (count_ == 0) return s;
  std::vector<float> sorted = durations_ms_;
  std::sort(sorted.begin(), sorted.end());
  s.p50_ms = nearest_rank(sorted, 0.50);
  s.p99_ms = nearest_rank(sorted, 0.99);
  s.p999_ms = nearest_rank(sorted, 0.999);
  s.max_ms = max_ms_;
  s.mean_ms = sum_ms_ / static_cast<double>(count_);
  return s;
}

}  // namespace tacta
