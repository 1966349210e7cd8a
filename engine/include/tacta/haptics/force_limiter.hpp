// Device force limiting: the force sent to a device never exceeds its declared peak (N). The
// limiter scales the whole vector (direction kept) and turns a non-finite force into zero, so a
// NaN from a model gives zero force in the same tick.
#pragma once

#include "tacta/vec3.hpp"

namespace tacta::haptics {

enum class ForceLimitResult { unchanged, scaled, non_finite_zeroed };

class ForceLimiter {
 public:
  explicit ForceLimiter(double peak_force) noexcept;  // N, > 0; a non-positive peak sends zero

  // Returns the limited force; `result` says what was done. |returned| <= peak_force() always.
  Vec3 limit(const Vec3& force, ForceLimitResult* result = nullptr) const noexcept;
  double peak_force() const noexcept { return peak_; }

 private:
  double peak_;
};

}  // namespace tacta::haptics
