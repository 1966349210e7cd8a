#include "systems/device_systems.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "systems/status_bits.hpp"
#include "tacta/sdk/pose.hpp"
#include "tacta/vec3.hpp"

namespace tacta {

namespace {

// A removed body is gone for the device too, and a frozen one could not be trusted: a device
// touching either renders nothing. A device that touches no body in particular is silenced by
// any frozen body.
bool touches_frozen_body(World& world, const DeviceComponents& dev) noexcept {
  if (dev.contact.touched_body >= 0) {
    const SoftBody b = world.body(static_cast<size_t>(dev.contact.touched_body));
    return b.fault.frozen || !b.present();
  }
  bool any = false;
  world.bodies_in_scene<FaultState>().each(
      [&](ecs::Entity, InScene&, FaultState& fault) { any = any || fault.frozen; });
  return any;
}

void log_sample(const DeviceComponents& dev, double sample_time, DeviceLogRecorder& log) noexcept {
  // Logged at the time the sample was read, so a replay at the same ticks is exact.
  DeviceLogSample logged;
  logged.time = sample_time;
  for (int a = 0; a < 3; ++a) {
    logged.position[a] = dev.link.sample.position[a];
    logged.velocity[a] = dev.link.sample.velocity[a];
    logged.force[a] = dev.contact.force[static_cast<size_t>(a)];
  }
  for (int a = 0; a < 4; ++a) logged.orientation[a] = dev.link.sample.orientation[a];
  logged.buttons = dev.link.sample.buttons;
  log.record(logged);
}

}  // namespace

void read_devices(World& world, TickEvents& events, double time) noexcept {
  world.registry().view<DeviceLink, DeviceStats>().each([&](ecs::Entity, DeviceLink& link,
                                                            DeviceStats& stats) {
    const size_t d = link.index;
    // A disconnected device (a network link gone silent) is polled on and resumes when it comes
    // back; finished and faulted ones stay so for the run.
    if (link.state != TACTA_DEVICE_CONNECTED && link.state != TACTA_DEVICE_DISCONNECTED) return;
    const bool was_disconnected = link.state == TACTA_DEVICE_DISCONNECTED;
    tacta_device_sample sample = link.sample;
    const tacta_device_state state = link.device->read(time, sample);
    if (was_disconnected) {
      if (state != TACTA_DEVICE_CONNECTED) {
        events.device_raised(d, kDeviceDisconnected);
        return;
      }
      link.state = TACTA_DEVICE_CONNECTED;  // the interaction restarts its proxy at the new pose
      ++stats.reconnections;
    }
    link.sample = sample;
    bool finite = true;
    for (double p : link.sample.position) finite = finite && std::isfinite(p);
    if (state == TACTA_DEVICE_CONNECTED && finite) return;
    link.state = state == TACTA_DEVICE_CONNECTED ? TACTA_DEVICE_FAULT : state;
    link.status_time_s = time;
    if (!finite)
      std::snprintf(link.status_reason.data(), link.status_reason.size(),
                    "device reported a non-finite position");
    else
      link.device->status(link.status_reason.data(), link.status_reason.size());
    if (link.state == TACTA_DEVICE_FAULT)
      events.device_raised(d, kDeviceFault);
    else if (link.state == TACTA_DEVICE_DISCONNECTED)
      events.device_raised(d, kDeviceDisconnected);
    if (state != TACTA_DEVICE_FINISHED) events.device_stopped(d, time);
  });
}

void write_devices(World& world, TickEvents& events, double time, double sample_time,
                   bool zero_force, DeviceLogRecorder* log) noexcept {
  world.registry().view<DeviceLink, DeviceContact, DeviceStats>().each(
      [&](ecs::Entity, DeviceLink& link, DeviceContact& contact, DeviceStats& st) {
        const DeviceComponents dev{link, contact, st};
        const size_t d = link.index;
        // From the faulting tick for as long as the body stays frozen.
        const bool silent = zero_force || dev.link.state != TACTA_DEVICE_CONNECTED ||
                            touches_frozen_body(world, dev);
        if (silent && dev.link.state == TACTA_DEVICE_CONNECTED)
          events.device_raised(d, kDeviceSilenced);
        if (silent) {
          dev.contact.force = {0, 0, 0};
          ++st.zero_force_ticks;
        }
        // The device's declared peak is never exceeded, whatever the coupling asked for.
        const double peak = dev.link.device->capabilities().peak_force;
        const double magnitude = norm(dev.contact.force.data());
        if (peak > 0 && magnitude > peak) {
          for (double& f : dev.contact.force) f *= peak / magnitude;
          ++st.clamped_ticks;
          events.device_raised(d, kDeviceClamped);
        }
        const double sent = std::min(magnitude, peak > 0 ? peak : magnitude);
        st.max_force_N = std::max(st.max_force_N, sent);
        if (dev.contact.in_contact) ++st.contact_ticks;
        if (d == 0 && log != nullptr) log_sample(dev, sample_time, *log);
        if (dev.link.state == TACTA_DEVICE_CONNECTED) {
          tacta_device_command command{};
          for (int a = 0; a < 3; ++a) command.force[a] = dev.contact.force[static_cast<size_t>(a)];
          dev.link.device->write(time, command);
        }
      });
}

void trace_devices(World& world, double time, double last_tick_ms,
                   Recorder<TraceRow>& trace) noexcept {
  world.registry().view<DeviceLink, DeviceContact>().each(
      [&](ecs::Entity, const DeviceLink& link, const DeviceContact& contact) {
        TraceRow row{time, link.index, {}, {}, {}, contact.in_contact ? 1u : 0u, last_tick_ms};
        for (int a = 0; a < 3; ++a) {
          row.position[a] = link.sample.position[a];
          row.proxy[a] = contact.proxy[static_cast<size_t>(a)];
          row.force[a] = contact.force[static_cast<size_t>(a)];
        }
        trace.push(row);
      });
}

void sweep_blades(World& world, double time) noexcept {
  for (size_t d = 0; d < world.device_count(); ++d) {
    BladeSweep& blade = world.tool(d).blade;
    if (!blade.enabled) continue;
    const DeviceComponents dev = world.device(d);
    dev.stats.held_blade = true;
    const tacta_device_sample& sample = dev.link.sample;
    const bool pressed =
        dev.link.state == TACTA_DEVICE_CONNECTED && (sample.buttons >> blade.desc.button & 1u) != 0;
    std::array<Vec3, 2> ends;
    for (size_t k = 0; k < 2; ++k) {
      double turned[3];
      sdk::rotate(sample.orientation, blade.desc.edge[k].data(), false, turned);
      for (size_t a = 0; a < 3; ++a) ends[k][a] = sample.position[a] + turned[a];
    }
    if (pressed && blade.held) {
      // The quad the edge swept this tick, as two triangles (last a, last b, b) and (last a, b, a).
      const std::array<Vec3, 6> corners{blade.last[0], blade.last[1], ends[1],
                                        blade.last[0], ends[1],       ends[0]};
      if (blade.swept.size() + 18 <= blade.swept.capacity()) {
        for (const Vec3& c : corners) blade.swept.insert(blade.swept.end(), c.begin(), c.end());
        if (blade.first_s < 0) blade.first_s = time;
      } else {
        blade.dropped += 2;
      }
    }
    if (!pressed && blade.held) blade.released = true;
    blade.held = pressed;
    blade.last = ends;
  }
}

}  // namespace tacta
