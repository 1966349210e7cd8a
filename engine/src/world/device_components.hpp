// The components of a device entity: its plugin link, the contact the haptic rendering made of
// its last tick, and the per-run statistics report.json gives for it.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "plugin/plugin_instance.hpp"
#include "tacta/ecs.hpp"
#include "tacta/scene.hpp"

namespace tacta {

struct DeviceStats {
  double max_force_N = 0;  // largest force sent
  // From the contact renderer (tacta/haptics/contact_renderer.hpp, ContactStatsParams):
  double first_contact_peak_N =
      0;                         // largest force in the onset window (0.25 s) of the first contact
  double steady_contact_N = 0;   // mean force over 0.4-0.5 s after the first contact began
  double energy_injected_J = 0;  // worst energy the coupling returned beyond what it took (J)
  double first_contact_time_s = -1;  // s, -1 before any contact
  uint64_t contact_ticks = 0;
  uint64_t zero_force_ticks = 0;  // ticks forced to zero force by a fault or disconnection
  uint64_t clamped_ticks = 0;     // ticks whose force was clamped to the peak
  uint64_t reconnections = 0;     // times a disconnected device came back (a network link)
  // Blades the device held (tool.blade), over every tool it carried: cuts made from their sweeps,
  // refused, and swept triangles past a sweep's capacity.
  uint64_t blade_cuts = 0, blade_cuts_refused = 0, blade_triangles_dropped = 0;
  bool held_blade = false;
};

// The device plugin and what it last said: its instance, the last sample, the connection state
// and why it stopped, and the tool it carries (an entity of its own).
struct DeviceLink {
  std::string name;
  uint32_t index = 0;  // in the scene's devices (trace, report, status counters)
  DeviceDesc desc;
  std::unique_ptr<DeviceInstance> device;
  tacta_device_sample sample{};
  tacta_device_state state = TACTA_DEVICE_CONNECTED;
  std::array<char, 200> status_reason{};  // why the device stopped, if it did
  double status_time_s = -1;
  ecs::Entity tool;  // the Tool entity it carries
};

// What the haptic rendering made of the device's last tick.
struct DeviceContact {
  std::array<double, 3> force{};  // N, last sent
  std::array<double, 3> proxy{};  // m, proxy (god-object) position
  bool in_contact = false;
  int touched_body = -1;  // index into the world's bodies, -1 when none
};

// One device's components by reference (World::device), for code that needs all of them.
struct DeviceComponents {
  DeviceLink& link;
  DeviceContact& contact;
  DeviceStats& stats;
};

}  // namespace tacta
