#include "tacta/haptics/first_contact.hpp"

#include <algorithm>

namespace tacta::haptics {

Vec3 FirstContactLimiter::shape(const Vec3& stretch, bool in_contact, double dt,
                                double max_stretch) noexcept {
  if (!in_contact) {
    reset();
    return stretch;
  }
  if (!onset_) return stretch;
  const double length = norm(stretch);
  if (!engaged_) {
    engaged_ = true;
    gap_ = length;  // the penetration the contact began with
  }
  const double step = params_.stretch_rate * dt;
  gap_ = std::max(gap_ - step, 0.0);
  // Caught up: no gap left, and the energy budget covers the true stretch to within one tick's
  // growth (the sampled spring's own lag keeps the budget a hair below the stretch).
  if (gap_ <= 0.0 && length <= max_stretch + step) {
    onset_ = false;  // normal contact from now on
    return stretch;
  }
  const double shaped = std::clamp(length - gap_, 0.0, std::max(max_stretch, 0.0));
  gap_ = length - shaped;  // the budget may hold the spring back further than the gap
  return length > 0.0 ? scaled(stretch, shaped / length) : stretch;
}

}  // namespace tacta::haptics
