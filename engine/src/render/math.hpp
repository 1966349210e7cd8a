// Small float vector and matrix helpers for the renderer (column-major 4x4, as GL expects).
#pragma once

#include <array>
#include <cmath>

#include "tacta/render/frame.hpp"
#include "tacta/sdk/pose.hpp"
#include "tacta/vec3.hpp"

namespace tacta::render::detail {

using Vec3f = std::array<float, 3>;
using Mat4 = std::array<float, 16>;  // column-major

inline Vec3f to_f(const Vec3d& v) {
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}
using tacta::add;
using tacta::cross;
using tacta::dot;
using tacta::norm;
using tacta::scaled;
using tacta::sub;
// Unit vector along a; `fallback` (up, +y) when a has no direction.
inline Vec3d normalized(const Vec3d& a, const Vec3d& fallback = {0, 1, 0}) {
  return tacta::normalized(a, fallback, 1e-300);
}

// Any unit vector perpendicular to the unit vector n.
inline Vec3d perpendicular(const Vec3d& n) {
  const Vec3d helper = std::fabs(n[0]) < 0.9 ? Vec3d{1, 0, 0} : Vec3d{0, 1, 0};
  return normalized(cross(n, helper));
}

// Rotates v by the unit quaternion q = (w, x, y, z).
inline Vec3d rotate(const std::array<double, 4>& q, const Vec3d& v) {
  Vec3d out;
  sdk::rotate(q.data(), v.data(), false, out.data());
  return out;
}

// q scaled to unit length; the identity when q is zero or not finite.
inline std::array<double, 4> unit_quaternion(const std::array<double, 4>& q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(n > 0) || !std::isfinite(n)) return {1, 0, 0, 0};
  return {q[0] / n, q[1] / n, q[2] / n, q[3] / n};
}

inline Mat4 multiply(const Mat4& a, const Mat4& b) {
  Mat4 r{};
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      float s = 0;
      for (int k = 0; k < 4; ++k)
        s += a[static_cast<size_t>(k * 4 + row)] * b[static_cast<size_t>(c * 4 + k)];
      r[static_cast<size_t>(c * 4 + row)] = s;
    }
  return r;
}

inline Mat4 look_at(const Vec3d& eye, const Vec3d& target, const Vec3d& up) {
  const Vec3d f = normalized(sub(target, eye), {0, 0, -1});
  const Vec3d s = normalized(cross(f, up), perpendicular(f));
  const Vec3d u = cross(s, f);
  Mat4 m{};
  m[0] = static_cast<float>(s[0]);
  m[4] = static_cast<float>(s[1]);
  m[8] = static_cast<float>(s[2]);
  m[1] = static_cast<float>(u[0]);
  m[5] = static_cast<float>(u[1]);
  m[9] = static_cast<float>(u[2]);
  m[2] = static_cast<float>(-f[0]);
  m[6] = static_cast<float>(-f[1]);
  m[10] = static_cast<float>(-f[2]);
  m[12] = static_cast<float>(-dot(s, eye));
  m[13] = static_cast<float>(-dot(u, eye));
  m[14] = static_cast<float>(dot(f, eye));
  m[15] = 1;
  return m;
}

inline Mat4 perspective(double fov_y_rad, double aspect, double near_m, double far_m) {
  const double f = 1.0 / std::tan(fov_y_rad / 2);
  Mat4 m{};
  m[0] = static_cast<float>(f / aspect);
  m[5] = static_cast<float>(f);
  m[10] = static_cast<float>((far_m + near_m) / (near_m - far_m));
  m[11] = -1;
  m[14] = static_cast<float>(2 * far_m * near_m / (near_m - far_m));
  return m;
}

inline Mat4 orthographic_pixels(int width, int height) {  // (0,0) top-left, y down
  Mat4 m{};
  m[0] = 2.0f / static_cast<float>(width);
  m[5] = -2.0f / static_cast<float>(height);
  m[10] = -1;
  m[12] = -1;
  m[13] = 1;
  m[15] = 1;
  return m;
}

}  // namespace tacta::render::detail
