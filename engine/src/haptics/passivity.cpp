#include "tacta/haptics/passivity.hpp"

#include <algorithm>

namespace tacta::haptics {

void PassivityController::reset(const Vec3& device_position) noexcept {
  last_position_ = device_position;
  last_sent_ = {0.0, 0.0, 0.0};
  started_ = true;
  energy_ = worst_deficit_ = dissipated_ = last_alpha_ = 0.0;
}

Vec3 PassivityController::update(const Vec3& device_position, const Vec3& device_velocity,
                                 double dt, const Vec3& desired_force, bool control) noexcept {
  if (!started_) reset(device_position);
  // Observer: exact work of the force held during the last tick, taken out of the environment.
  energy_ -= dot(last_sent_, sub(device_position, last_position_));
  last_position_ = device_position;
  worst_deficit_ = std::max(worst_deficit_, -energy_);
  last_alpha_ = 0.0;
  if (!control || !params_.controller_enabled || !(dt > 0.0)) return desired_force;

  const double speed_squared = dot(device_velocity, device_velocity);
  const double predicted = energy_ - dot(desired_force, device_velocity) * dt;
  if (predicted >= 0.0 || speed_squared < params_.min_speed * params_.min_speed)
    return desired_force;
  const double alpha = std::min(-predicted / (speed_squared * dt), params_.max_damping);
  last_alpha_ = alpha;
  dissipated_ += alpha * speed_squared * dt;
  return add_scaled(desired_force, device_velocity, -alpha);
}

}  // namespace tacta::haptics
