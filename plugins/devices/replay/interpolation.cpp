#include "interpolation.hpp"

#include <algorithm>
#include <cmath>

namespace tacta::replay {

void slerp(const double a[4], const double b[4], double s, double out[4]) noexcept {
  double cosine = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
  const double sign = cosine < 0.0 ? -1.0 : 1.0;  // q and -q are one rotation: take the short arc
  cosine *= sign;
  double wa = 1.0 - s;
  double wb = s;
  if (cosine < 0.9995) {  // else nearly parallel: normalised lerp is accurate and stable
    const double angle = std::acos(std::min(cosine, 1.0));
    const double sine = std::sin(angle);
    wa = std::sin((1.0 - s) * angle) / sine;
    wb = std::sin(s * angle) / sine;
  }
  double length_squared = 0.0;
  for (int i = 0; i < 4; ++i) {
    out[i] = wa * a[i] + wb * sign * b[i];
    length_squared += out[i] * out[i];
  }
  const double inverse = length_squared > 0.0 ? 1.0 / std::sqrt(length_squared) : 0.0;
  for (int i = 0; i < 4; ++i) out[i] *= inverse;
}

DeviceLogSample sample_at(std::span<const DeviceLogSample> samples, double time) noexcept {
  if (time <= samples.front().time) return samples.front();
  if (time >= samples.back().time) return samples.back();
  // First sample strictly after `time`; the one before it is at or before `time`.
  const auto after =
      std::upper_bound(samples.begin(), samples.end(), time,
                       [](double t, const DeviceLogSample& s) { return t < s.time; });
  const DeviceLogSample& b = *after;
  const DeviceLogSample& a = *(after - 1);
  if (time == a.time) return a;                          // exact at the samples, bit for bit
  const double s = (time - a.time) / (b.time - a.time);  // b.time > time > a.time
  DeviceLogSample out = a;
  out.time = time;
  for (int i = 0; i < 3; ++i) {
    out.position[i] = a.position[i] + (b.position[i] - a.position[i]) * s;
    out.velocity[i] = a.velocity[i] + (b.velocity[i] - a.velocity[i]) * s;
    out.force[i] = a.force[i] + (b.force[i] - a.force[i]) * s;
  }
  slerp(a.orientation, b.orientation, s, out.orientation);
  out.buttons = a.buttons;
  return out;
}

}  // namespace tacta::replay
