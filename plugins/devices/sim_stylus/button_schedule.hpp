// When the scripted hand holds the stylus button (bit 0): press and release times, s, in pairs
// [press0, release0, press1, release1, ...]; the button is down for t in [press_k, release_k).
// Built once at create (throws std::invalid_argument), read in the 1 kHz path (noexcept, no
// allocation).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tacta::sim_stylus {

class ButtonSchedule {
 public:
  explicit ButtonSchedule(std::span<const double> times);  // validates; copies the times
  uint32_t buttons(double time) const noexcept;            // the button bits at `time`

 private:
  std::vector<double> times_;  // ascending press, release pairs
};

}  // namespace tacta::sim_stylus
