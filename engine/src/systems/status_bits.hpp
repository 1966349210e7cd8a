// The one table of run-time status bits (after Jolt's EPhysicsUpdateError): for each source
// (model step, collision pipeline, device) bit -> name -> severity -> remedy, and the fixed-size
// per-tick counters the haptic thread fills without allocating.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "tacta/sim/run_status.hpp"

namespace tacta {

enum class StatusSource { Model, Collision, Device };

// Device bits are the engine's (the device API reports a state, not bits).
constexpr uint32_t kDeviceDisconnected = 1u << 0;  // polled, no data this tick
constexpr uint32_t kDeviceFault = 1u << 1;         // faulted (itself, or a non-finite position)
constexpr uint32_t kDeviceClamped = 1u << 2;       // force clamped to the device's peak
constexpr uint32_t kDeviceSilenced = 1u << 3;      // force zeroed: a fault or a frozen body

struct StatusBitInfo {
  StatusSource source;
  uint32_t bit;
  const char* name;
  StatusSeverity severity;
  const char* remedy;
};

std::span<const StatusBitInfo> status_bit_table() noexcept;
// The table's entry, or null for a bit it does not know (reported as "bit_N", a warning).
const StatusBitInfo* status_bit_info(StatusSource source, uint32_t bit) noexcept;

// True when any of `bits` is an error in the table (noexcept, no allocation).
bool has_error_bit(StatusSource source, uint32_t bits) noexcept;

// Ticks each of 32 bits was seen on, and when first; fixed arrays, noexcept, no allocation.
struct StatusCounter {
  std::array<uint64_t, 32> ticks{};
  std::array<double, 32> first_time_s{};
  uint32_t seen = 0;
  void add(uint32_t bits, double time) noexcept {
    for (uint32_t rest = bits; rest != 0; rest &= rest - 1) {
      const int b = __builtin_ctz(rest);
      if (ticks[static_cast<size_t>(b)]++ == 0) first_time_s[static_cast<size_t>(b)] = time;
    }
    seen |= bits;
  }
  bool has_error(StatusSource source) const noexcept { return has_error_bit(source, seen); }
};

// The counter as the report lists it (info bits included), in bit order.
std::vector<StatusBitCount> describe(const StatusCounter& counter, StatusSource source);

}  // namespace tacta
