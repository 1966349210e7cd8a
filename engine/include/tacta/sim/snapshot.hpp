// What the haptic task publishes for the render task at each frame: copies of the state, made
// into buffers sized at load time (no allocation in the 1 kHz path).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tacta {

struct BodySnapshot {
  std::vector<double> positions;   // 3 per node, m
  std::vector<double> von_mises;   // 1 per node, Pa (empty when the model gives no stress)
  std::string model;               // model name at the time of the snapshot (set at swaps only)
  bool frozen = false;
  double kinetic_J = 0, elastic_J = 0, max_displacement_m = 0;
};

struct DeviceSnapshot {
  std::array<double, 3> position{};  // m
  std::array<double, 3> proxy{};     // m
  std::array<double, 3> force{};     // N, as sent to the device
  bool contact = false;
};

struct Snapshot {
  double time_s = 0;
  uint64_t tick = 0;
  double last_tick_ms = 0;
  std::vector<BodySnapshot> bodies;
  std::vector<DeviceSnapshot> devices;
};

}  // namespace tacta
