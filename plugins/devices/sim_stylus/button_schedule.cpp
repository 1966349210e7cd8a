#include "button_schedule.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tacta::sim_stylus {

ButtonSchedule::ButtonSchedule(std::span<const double> times) : times_(times.begin(), times.end()) {
  if (times_.size() % 2 != 0)
    throw std::invalid_argument(
        "sim_stylus: button_times expects press and release times in pairs (s), found " +
        std::to_string(times_.size()) + " numbers");
  for (size_t i = 0; i < times_.size(); ++i) {
    if (!std::isfinite(times_[i]))
      throw std::invalid_argument("sim_stylus: button_times[" + std::to_string(i) +
                                  "]: expected a finite time (s)");
    if (i > 0 && !(times_[i] > times_[i - 1]))
      throw std::invalid_argument(
          "sim_stylus: button_times[" + std::to_string(i) + "] = " + std::to_string(times_[i]) +
          " s: expected a time after the previous one (" + std::to_string(times_[i - 1]) +
          " s); the list is press, release, press, release, ... ascending");
  }
}

uint32_t ButtonSchedule::buttons(double time) const noexcept {
  // The number of times at or before `time`: odd inside a [press, release) window.
  const auto after = std::upper_bound(times_.begin(), times_.end(), time);
  return (after - times_.begin()) % 2 == 1 ? 1u : 0u;
}

}  // namespace tacta::sim_stylus
