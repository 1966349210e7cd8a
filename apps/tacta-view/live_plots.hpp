// Ring buffers for the live plots (Dear ImGui PlotLines reads them with an offset).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace tacta::view {

template <size_t N>
class RingPlot {
 public:
  void push(float value) {
    samples_[next_] = value;
    next_ = (next_ + 1) % N;
    count_ = std::min(count_ + 1, N);
  }
  const float* data() const { return samples_.data(); }
  int size() const { return static_cast<int>(N); }
  int offset() const { return static_cast<int>(next_); }  // the oldest sample
  float max() const {
    return count_ == 0 ? 0.0f : *std::max_element(samples_.begin(), samples_.end());
  }
  float latest() const { return count_ == 0 ? 0.0f : samples_[(next_ + N - 1) % N]; }

 private:
  std::array<float, N> samples_{};
  size_t next_ = 0;
  size_t count_ = 0;
};

}  // namespace tacta::view
