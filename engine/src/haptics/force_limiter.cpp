#include "tacta/haptics/force_limiter.hpp"

namespace tacta::haptics {

ForceLimiter::ForceLimiter(double peak_force) noexcept
    : peak_(std::isfinite(peak_force) && peak_force > 0.0 ? peak_force : 0.0) {}

Vec3 ForceLimiter::limit(const Vec3& force, ForceLimitResult* result) const noexcept {
  if (!is_finite(force)) {
    if (result) *result = ForceLimitResult::non_finite_zeroed;
    return {0.0, 0.0, 0.0};
  }
  const double magnitude = std::hypot(force[0], force[1], force[2]);  // no overflow for huge forces
  if (magnitude <= peak_) {
    if (result) *result = ForceLimitResult::unchanged;
    return force;
  }
  if (result) *result = ForceLimitResult::scaled;
  // Scale slightly inside the peak so rounding can never leave |f| a hair above it.
  const double factor = peak_ / magnitude * (1.0 - 1e-12);
  return scaled(force, factor);
}

}  // namespace tacta::haptics
