// The haptic task's device systems: free functions over the World's device entities, called by
// HapticLoop::tick at the start (read) and the end (write, trace) of a tick. Each runs on the
// tick's thread and allocates nothing, takes no lock, throws nothing.
#pragma once

#include "output/recorders.hpp"
#include "systems/tick_events.hpp"
#include "tacta/device_log.hpp"
#include "world/world.hpp"

namespace tacta {

// Samples every connected device (and polls disconnected ones, which resume when they answer).
// A device that faults, finishes or sends a non-finite position stops here.
void read_devices(World& world, TickEvents& events, double time) noexcept;

// Each blade tool whose button is held adds what its edge swept since the last tick (two
// triangles, world frame, from the device's sampled pose: the hand, not the proxy held on the
// surface) to its sweep; letting the button go marks the sweep for cutting.
void sweep_blades(World& world, double time) noexcept;

// Sends each device its force at `time`: zero after any fault this tick (`zero_force`), while it
// touches a frozen or removed body, or when it is not connected; clamped to its peak. The first
// device's sample and sent force go to `log` (may be null), stamped `sample_time`.
void write_devices(World& world, TickEvents& events, double time, double sample_time,
                   bool zero_force, DeviceLogRecorder* log) noexcept;

// One trace row per device: position, proxy, force, contact and the last tick's duration.
void trace_devices(World& world, double time, double last_tick_ms,
                   Recorder<TraceRow>& trace) noexcept;

}  // namespace tacta
