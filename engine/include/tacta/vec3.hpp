// 3-vector helpers for the engine, the apps and plugins: std::array<double, 3> (or three doubles
// behind a pointer, as flat position arrays hold them). constexpr where the standard allows,
// noexcept and allocation-free, so the 1 kHz path may use all of them. Eigen-based code keeps
// Eigen; this is for the places that hand-rolled these few lines.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace tacta {

using Vec3 = std::array<double, 3>;  // same alias as scene.hpp

// Point i of a flat array of 3 doubles per point.
constexpr Vec3 point_at(const double* flat, size_t i) noexcept {
  return {flat[3 * i], flat[3 * i + 1], flat[3 * i + 2]};
}

constexpr Vec3 add(const Vec3& a, const Vec3& b) noexcept {
  return {a[0] + b[0], a[1] + b[1], a[2] + b[2]};
}
constexpr Vec3 sub(const Vec3& a, const Vec3& b) noexcept {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
constexpr Vec3 scaled(const Vec3& a, double s) noexcept { return {a[0] * s, a[1] * s, a[2] * s}; }
// a + s * b
constexpr Vec3 add_scaled(const Vec3& a, const Vec3& b, double s) noexcept {
  return {a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]};
}

constexpr double dot(const Vec3& a, const Vec3& b) noexcept {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
constexpr double dot(const double* a, const double* b) noexcept {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
constexpr Vec3 cross(const Vec3& a, const Vec3& b) noexcept {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
constexpr Vec3 cross(const double* a, const double* b) noexcept {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
// a . (b x c): six times the signed volume of the tet (0, a, b, c).
constexpr double triple(const Vec3& a, const Vec3& b, const Vec3& c) noexcept {
  return dot(a, cross(b, c));
}

constexpr double squared_norm(const Vec3& a) noexcept { return dot(a, a); }
inline double norm(const Vec3& a) noexcept { return std::sqrt(dot(a, a)); }
inline double norm(const double* a) noexcept { return std::sqrt(dot(a, a)); }
inline double distance(const Vec3& a, const Vec3& b) noexcept { return norm(sub(a, b)); }
// a / |a|, or `fallback` when |a| is not above `tiny` (a zero or denormal vector has no direction).
inline Vec3 normalized(const Vec3& a, const Vec3& fallback = {0, 0, 0},
                       double tiny = 0.0) noexcept {
  const double n = norm(a);
  return n > tiny ? scaled(a, 1.0 / n) : fallback;
}

inline bool is_finite(const Vec3& a) noexcept {
  return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}

}  // namespace tacta
