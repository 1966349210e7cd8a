// Small 3-vector helpers for the haptic classes (no Eigen in public headers). All noexcept and
// allocation-free, for the 1 kHz path.
#pragma once

#include <array>
#include <cmath>

namespace tacta {

using Vec3 = std::array<double, 3>;  // same alias as scene.hpp

namespace haptics {

constexpr Vec3 add(const Vec3& a, const Vec3& b) noexcept { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
constexpr Vec3 sub(const Vec3& a, const Vec3& b) noexcept { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
constexpr Vec3 scaled(const Vec3& a, double s) noexcept { return {a[0] * s, a[1] * s, a[2] * s}; }
constexpr double dot(const Vec3& a, const Vec3& b) noexcept { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline double norm(const Vec3& a) noexcept { return std::sqrt(dot(a, a)); }
inline bool is_finite(const Vec3& a) noexcept {
  return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}
// a + s * b
constexpr Vec3 add_scaled(const Vec3& a, const Vec3& b, double s) noexcept {
  return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]};
}

}  // namespace haptics
}  // namespace tacta
