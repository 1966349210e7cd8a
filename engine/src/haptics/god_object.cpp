#include "tacta/haptics/god_object.hpp"

namespace tacta::haptics {

void GodObjectProxy::reset(const Vec3& device_position) noexcept {
  position_ = device_position;
  velocity_ = {0.0, 0.0, 0.0};
  in_contact_ = false;
  contact_ = {};
}

Vec3 GodObjectProxy::on_surface(const SurfaceHit& hit) const noexcept {
  return add_scaled(hit.point, hit.normal, params_.radius + params_.skin);
}

void GodObjectProxy::update(const SurfaceQuery& world, const Vec3& device_position,
                            const Vec3& device_velocity) noexcept {
  if (!is_finite(device_position)) return;  // keep the last proxy; the engine zeroes the force
  if (!in_contact_) {
    SurfaceHit hit;
    double signed_distance = 0.0;
    if (world.first_hit(position_, device_position, params_.radius, hit)) {
      contact_ = hit;
      position_ = on_surface(hit);
      in_contact_ = true;
    } else if (world.closest_point(device_position, params_.inside_search, hit, signed_distance) &&
               signed_distance < params_.radius) {
      // Overlapping without a sweep hit: a surface came onto the device, or it started inside.
      contact_ = hit;
      position_ = on_surface(hit);
      in_contact_ = true;
    } else {
      position_ = device_position;
      velocity_ = device_velocity;
      return;
    }
  }
  if (!move_in_contact(world, device_position)) {
    velocity_ = device_velocity;
    return;
  }
  const Vec3& n = contact_.normal;
  velocity_ = add_scaled(device_velocity, n, -dot(device_velocity, n));
}

bool GodObjectProxy::move_in_contact(const SurfaceQuery& world, const Vec3& device) noexcept {
  for (int iteration = 0; iteration < params_.max_iterations; ++iteration) {
    const Vec3 n = contact_.normal;
    const Vec3 toward_device = sub(device, position_);
    const double normal_part = dot(toward_device, n);
    SurfaceHit hit;
    if (normal_part >= 0.0) {
      // The device is on the free side of the contact plane: follow it unless something is in the way.
      if (!world.first_hit(position_, device, params_.radius, hit)) {
        position_ = device;
        in_contact_ = false;
        return false;
      }
      contact_ = hit;
      position_ = on_surface(hit);
      continue;
    }
    // Slide on the tangent plane toward the device's projection on it.
    const Vec3 goal = add_scaled(device, n, -normal_part);  // at the proxy's height
    const Vec3 start = position_;
    if (world.first_hit(position_, goal, params_.radius, hit)) {
      contact_ = hit;
      position_ = on_surface(hit);
      continue;
    }
    position_ = goal;
    // A curved surface falls away from the tangent plane: put the proxy back on it.
    double signed_distance = 0.0;
    if (world.closest_point(position_, params_.inside_search + params_.radius, hit, signed_distance)) {
      contact_ = hit;
      position_ = on_surface(hit);
    }
    const Vec3 moved = sub(position_, start);
    if (dot(moved, moved) < 1e-24) break;  // converged (1e-12 m)
  }
  return true;
}

}  // namespace tacta::haptics
