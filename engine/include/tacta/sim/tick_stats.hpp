// Tick durations, recorded without allocation into a buffer sized before the run, and their
// percentiles afterwards.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tacta {

struct TickSummary {
  uint64_t ticks = 0;
  double p50_ms = 0, p99_ms = 0, p999_ms = 0, max_ms = 0, mean_ms = 0;
};

class TickRecorder {
 public:
  // capacity: ticks to keep; later ticks still count in max and mean, not in percentiles.
  explicit TickRecorder(size_t capacity = 0) { durations_ms_.reserve(capacity); }
  void reserve(size_t capacity) { durations_ms_.reserve(capacity); }
  // Room for `more` durations past those kept, `limit` in all; later ticks count in max and mean.
  void grow(size_t more, size_t limit) {
    durations_ms_.reserve(
        std::min(durations_ms_.size() + more, std::max(limit, durations_ms_.capacity())));
  }

  void record(double duration_ms) noexcept {
    ++count_;
    sum_ms_ += duration_ms;
    if (duration_ms > max_ms_) max_ms_ = duration_ms;
    if (durations_ms_.size() < durations_ms_.capacity())
      durations_ms_.push_back(static_cast<float>(duration_ms));
  }
  uint64_t count() const noexcept { return count_; }
  TickSummary summary() const;  // sorts a copy; call after the run
  const std::vector<float>& durations_ms() const noexcept { return durations_ms_; }

 private:
  std::vector<float> durations_ms_;  // push_back within reserved capacity never allocates
  uint64_t count_ = 0;
  double sum_ms_ = 0;
  double max_ms_ = 0;
};

}  // namespace tacta
