#include "tacta/haptics/first_contact.hpp"

namespace tacta::haptics {

Vec3 FirstContactLimiter::shape(const Vec3& stretch, bool in_contact, double dt) noexcept {
  if (!in_contact) {
    reset();
    return stretch;
  }
  if (!onset_) return stretch;
  allowed_ += params_.stretch_rate * dt;
  const double length = norm(stretch);
  if (length <= allowed_) {
    onset_ = false;  // caught up: normal contact from now on
    return stretch;
  }
  return scaled(stretch, allowed_ / length);
}

}  // namespace tacta::haptics
