// The Device component: a device plugin instance, the tool it carries, its last sample and the
// force it was last sent, plus the per-run statistics report.json gives for it.
#pragma once

#include <array>
#include <memory>
#include <string>

#include "plugin_instance.hpp"
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
  uint64_t tool_changes = 0;      // tools changed while the scene ran (events, stepping API)
};

struct DeviceSlot {
  std::string name;
  uint32_t index = 0;  // in the scene's devices (trace, report, status counters)
  ecs::Entity tool;    // the Tool entity it carries
  DeviceDesc desc;
  std::unique_ptr<DeviceInstance> device;
  tacta_device_sample sample{};
  tacta_device_state state = TACTA_DEVICE_CONNECTED;
  std::array<double, 3> force{};  // N, last sent
  std::array<double, 3> proxy{};  // m, proxy (god-object) position
  bool in_contact = false;
  int touched_body = -1;  // index into the world's bodies, -1 when none
  DeviceStats stats;
  std::array<char, 200> status_reason{};  // why the device stopped, if it did
  double status_time_s = -1;
};

}  // namespace tacta
