// The monotonic clock the network devices and their clients stamp with (CLOCK_MONOTONIC, the
// clock tacta_net_device.h and tacta_net_device.py use), in s and in ns.
#pragma once

#include <cstdint>
#include <ctime>

namespace tacta::devices {

inline uint64_t monotonic_ns() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<uint64_t>(t.tv_sec) * 1000000000ull + static_cast<uint64_t>(t.tv_nsec);
}

inline double monotonic_seconds() noexcept {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec) * 1e-9;
}

}  // namespace tacta::devices
