// Round-trip times a network device measured, for report.json: a ring of the newest samples,
// written by the device's network thread, summarised (p50, p99) by the host after the run.
// Never touched by the 1 kHz path, so a mutex is fine here.
#pragma once

#include <algorithm>
#include <cstddef>
#include <mutex>
#include <vector>

namespace tacta::devices {

class RoundTripLog {
 public:
  explicit RoundTripLog(size_t capacity = 1 << 16) : samples_(capacity) {}

  void add(double seconds) {
    std::lock_guard<std::mutex> lock(mutex_);
    samples_[next_ % samples_.size()] = seconds;
    ++next_;
  }
  size_t count() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return std::min(next_, samples_.size());
  }
  // The q-quantile (0..1) in seconds of the samples kept, -1 when there are none.
  double quantile(double q) const {
    std::vector<double> kept;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      kept.assign(samples_.begin(),
                  samples_.begin() + static_cast<std::ptrdiff_t>(std::min(next_, samples_.size())));
    }
    if (kept.empty()) return -1.0;
    const auto k = static_cast<size_t>(q * static_cast<double>(kept.size() - 1) + 0.5);
    std::nth_element(kept.begin(), kept.begin() + static_cast<std::ptrdiff_t>(k), kept.end());
    return kept[k];
  }

 private:
  mutable std::mutex mutex_;
  std::vector<double> samples_;  // s
  size_t next_ = 0;
};

}  // namespace tacta::devices
