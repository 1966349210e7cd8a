#include "device_systems.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "status_bits.hpp"
#include "tacta/vec3.hpp"

namespace tacta {

namespace {

// A removed body is gone for the device too, and a frozen one could not be trusted: a device
// touching either renders nothing. A device that touches no body in particular is silenced by
// any frozen body.
bool touches_frozen_body(World& world, const DeviceSlot& slot) noexcept {
  if (slot.touched_body >= 0) {
    const SoftBody b = world.body(static_cast<size_t>(slot.touched_body));
    return b.fault.frozen || !b.present();
  }
  bool any = false;
  world.bodies_in_scene<FaultState>().each(
      [&](ecs::Entity, InScene&, FaultState& fault) { any = any || fault.frozen; });
  return any;
}

void log_sample(const DeviceSlot& slot, double sample_time, DeviceLogRecorder& log) noexcept {
  // Logged at the time the sample was read, so a replay at the same ticks is exact.
  DeviceLogSample logged;
  logged.time = sample_time;
  for (int a = 0; a < 3; ++a) {
    logged.position[a] = slot.sample.position[a];
    logged.velocity[a] = slot.sample.velocity[a];
    logged.force[a] = slot.force[static_cast<size_t>(a)];
  }
  for (int a = 0; a < 4; ++a) logged.orientation[a] = slot.sample.orientation[a];
  logged.buttons = slot.sample.buttons;
  log.record(logged);
}

}  // namespace

void read_devices(World& world, TickEvents& events, double time) noexcept {
  world.registry().view<DeviceSlot>().each([&](ecs::Entity, DeviceSlot& slot) {
    const size_t d = slot.index;
    // A disconnected device (a network link gone silent) is polled on and resumes when it comes
    // back; finished and faulted ones stay so for the run.
    if (slot.state != TACTA_DEVICE_CONNECTED && slot.state != TACTA_DEVICE_DISCONNECTED) return;
    const bool was_disconnected = slot.state == TACTA_DEVICE_DISCONNECTED;
    tacta_device_sample sample = slot.sample;
    const tacta_device_state state = slot.device->read(time, sample);
    if (was_disconnected) {
      if (state != TACTA_DEVICE_CONNECTED) {
        events.device_raised(d, kDeviceDisconnected);
        return;
      }
      slot.state = TACTA_DEVICE_CONNECTED;  // the interaction restarts its proxy at the new pose
      ++slot.stats.reconnections;
    }
    slot.sample = sample;
    bool finite = true;
    for (double p : slot.sample.position) finite = finite && std::isfinite(p);
    if (state == TACTA_DEVICE_CONNECTED && finite) return;
    slot.state = state == TACTA_DEVICE_CONNECTED ? TACTA_DEVICE_FAULT : state;
    slot.status_time_s = time;
    if (!finite)
      std::snprintf(slot.status_reason.data(), slot.status_reason.size(),
                    "device reported a non-finite position");
    else
      slot.device->status(slot.status_reason.data(), slot.status_reason.size());
    if (slot.state == TACTA_DEVICE_FAULT)
      events.device_raised(d, kDeviceFault);
    else if (slot.state == TACTA_DEVICE_DISCONNECTED)
      events.device_raised(d, kDeviceDisconnected);
    if (state != TACTA_DEVICE_FINISHED) events.device_stopped(d, time);
  });
}

void write_devices(World& world, TickEvents& events, double time, double sample_time,
                   bool zero_force, DeviceLogRecorder* log) noexcept {
  world.registry().view<DeviceSlot>().each([&](ecs::Entity, DeviceSlot& slot) {
    const size_t d = slot.index;
    DeviceStats& st = slot.stats;
    // From the faulting tick for as long as the body stays frozen.
    const bool silent =
        zero_force || slot.state != TACTA_DEVICE_CONNECTED || touches_frozen_body(world, slot);
    if (silent && slot.state == TACTA_DEVICE_CONNECTED) events.device_raised(d, kDeviceSilenced);
    if (silent) {
      slot.force = {0, 0, 0};
      ++st.zero_force_ticks;
    }
    // The device's declared peak is never exceeded, whatever the coupling asked for.
    const double peak = slot.device->capabilities().peak_force;
    const double magnitude = norm(slot.force.data());
    if (peak > 0 && magnitude > peak) {
      for (double& f : slot.force) f *= peak / magnitude;
      ++st.clamped_ticks;
      events.device_raised(d, kDeviceClamped);
    }
    const double sent = std::min(magnitude, peak > 0 ? peak : magnitude);
    st.max_force_N = std::max(st.max_force_N, sent);
    if (slot.in_contact) ++st.contact_ticks;
    if (d == 0 && log != nullptr) log_sample(slot, sample_time, *log);
    if (slot.state == TACTA_DEVICE_CONNECTED) {
      tacta_device_command command{};
      for (int a = 0; a < 3; ++a) command.force[a] = slot.force[static_cast<size_t>(a)];
      slot.device->write(time, command);
    }
  });
}

void trace_devices(World& world, double time, double last_tick_ms,
                   Recorder<TraceRow>& trace) noexcept {
  world.registry().view<DeviceSlot>().each([&](ecs::Entity, const DeviceSlot& s) {
    TraceRow row{time, s.index, {}, {}, {}, s.in_contact ? 1u : 0u, last_tick_ms};
    for (int a = 0; a < 3; ++a) {
      row.position[a] = s.sample.position[a];
      row.proxy[a] = s.proxy[static_cast<size_t>(a)];
      row.force[a] = s.force[static_cast<size_t>(a)];
    }
    trace.push(row);
  });
}

}  // namespace tacta
