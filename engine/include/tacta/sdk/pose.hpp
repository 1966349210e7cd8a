// Rigid poses for plugins and the engine alike (tacta_pose: position, unit quaternion w, x, y, z).
#pragma once

namespace tacta::sdk {

// Rotates v by the unit quaternion q = (w, x, y, z), or by its inverse:
// v + 2 w (u x v) + 2 u x (u x v), with u = (x, y, z). `out` may not alias v.
inline void rotate(const double* q, const double* v, bool inverse, double* out) noexcept {
  const double w = q[0], x = inverse ? -q[1] : q[1], y = inverse ? -q[2] : q[2],
               z = inverse ? -q[3] : q[3];
  const double t[3] = {2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]),
                       2 * (x * v[1] - y * v[0])};
  out[0] = v[0] + w * t[0] + (y * t[2] - z * t[1]);
  out[1] = v[1] + w * t[1] + (z * t[0] - x * t[2]);
  out[2] = v[2] + w * t[2] + (x * t[1] - y * t[0]);
}

}  // namespace tacta::sdk
