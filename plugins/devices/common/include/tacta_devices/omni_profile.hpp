// The Phantom Omni class device that the simulated devices (sim_stylus, mouse) stand in for:
// its numbers (docs/REFERENCES.md: workspace about 160 x 120 x 70 mm, peak force 3.3 N,
// continuous about 0.88 N, usable stiffness about 1 N/mm at 1 kHz), its force saturation and
// its capabilities record.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "tacta/device_api.h"

namespace tacta::devices {

using Point = std::array<double, 3>;

inline constexpr double kOmniPeakForce = 3.3;           // N
inline constexpr double kOmniContinuousForce = 0.88;    // N
inline constexpr double kOmniUsableStiffness = 1000.0;  // N/m (1 N/mm at 1 kHz)
inline constexpr Point kOmniWorkspaceHalf{0.080, 0.060,
                                          0.035};  // m: 160 wide (x), 120 high (y), 70 deep (z)

// The force the motors can render: the command scaled down to the peak (direction kept), and
// zero for a non-finite command.
inline Point saturate_force(const double command[3]) noexcept {
  const double magnitude = std::hypot(command[0], command[1], command[2]);
  if (!std::isfinite(magnitude)) return {0.0, 0.0, 0.0};
  const double scale = magnitude > kOmniPeakForce ? kOmniPeakForce / magnitude : 1.0;
  return {command[0] * scale, command[1] * scale, command[2] * scale};
}

// Holds a simulated stylus inside the workspace centred on `origin` along `axis` (0 x, 1 y,
// 2 z): at a wall the position (m) stays on it and the velocity (m/s) into it is dropped.
inline void stop_at_workspace(const Point& origin, size_t axis, Point& position,
                              Point& velocity) noexcept {
  const double low = origin[axis] - kOmniWorkspaceHalf[axis];
  const double high = origin[axis] + kOmniWorkspaceHalf[axis];
  if (position[axis] < low) {
    position[axis] = low;
    velocity[axis] = std::max(velocity[axis], 0.0);
  }
  if (position[axis] > high) {
    position[axis] = high;
    velocity[axis] = std::min(velocity[axis], 0.0);
  }
}

// Capabilities of an Omni whose workspace is centred on `origin` (m, world frame), at 1 kHz.
inline tacta_device_capabilities omni_capabilities(const Point& origin, uint32_t dof_in) noexcept {
  tacta_device_capabilities c{};
  for (int i = 0; i < 3; ++i) {
    c.workspace_min[i] =
        origin[static_cast<size_t>(i)] - kOmniWorkspaceHalf[static_cast<size_t>(i)];
    c.workspace_max[i] =
        origin[static_cast<size_t>(i)] + kOmniWorkspaceHalf[static_cast<size_t>(i)];
  }
  c.peak_force = kOmniPeakForce;
  c.continuous_force = kOmniContinuousForce;
  c.usable_stiffness = kOmniUsableStiffness;
  c.nominal_rate = 1000.0;
  c.dof_in = dof_in;
  c.dof_out = 3;  // forces only
  return c;
}

}  // namespace tacta::devices
