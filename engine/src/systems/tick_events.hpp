// What the tick's systems tell the tick's ledger (HapticLoop: status counters per body and
// device, fault records). Called on the tick's thread; implementations allocate nothing.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tacta {

class TickEvents {
 public:
  virtual ~TickEvents() = default;
  // Every model step taken, with its TACTA_STEP_* bits.
  virtual void stepped(size_t body, uint32_t bits, double time) noexcept = 0;
  // A step that faulted: the body's state is already back at the step's start.
  virtual void faulted(size_t body, uint32_t bits, const char* why, double time) noexcept = 0;
  // A device status bit (status_bits.hpp: kDevice*) raised this tick.
  virtual void device_raised(size_t device, uint32_t bit) noexcept = 0;
  // A device stopped (fault or disconnection; DeviceLink::status_reason says why).
  virtual void device_stopped(size_t device, double time) noexcept = 0;
};

}  // namespace tacta
