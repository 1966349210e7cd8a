// Interpolation of logged device samples to an arbitrary time (1 kHz path: noexcept, no
// allocation). Position and velocity: linear. Orientation: slerp on the shorter arc, normalised
// lerp when the two are nearly equal. Buttons: from the earlier sample. Exactly the stored sample
// at a sample's own time.
#pragma once

#include <span>

#include "tacta/device_log.hpp"

namespace tacta::replay {

// samples: non-decreasing in time, at least one. Times before the first give the first sample,
// after the last the last one.
DeviceLogSample sample_at(std::span<const DeviceLogSample> samples, double time) noexcept;

// Spherical interpolation of unit quaternions (w, x, y, z) a -> b by s in [0, 1].
void slerp(const double a[4], const double b[4], double s, double out[4]) noexcept;

}  // namespace tacta::replay
