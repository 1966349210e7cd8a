#include "tacta/haptics/god_object.hpp"

namespace tacta::haptics {

void GodObjectProxy::reset(const Vec3& device_position) noexcept {
  position_ = device_position;
  velocity_ = {0.0, 0.0, 0.0};
  in_contact_ = false;
  contact_ = {};
}

Vec3 GodObjectProxy::on_surface(SurfaceHit& hit, const Vec3& centre) const noexcept {
  // The sphere touches the surface at hit.point with its centre along the line from that point to
  // `centre` (the sweep's centre at contact, or the point that was projected). On a face that line
  // is the face normal; at an edge or a vertex of a triangle mesh it is not, and placing the
  // centre along the touched face's normal instead moved the 4 mm tool tip sideways by up to
  // r sin(angle between faces) each time the closest point crossed an edge: in the liver demo the
  // proxy flipped by ~1 mm between two positions every tick at release (lateral force steps of
  // ~0.3 N, and pulls of 0.2 N along -y). Along that line the distance to the surface is
  // continuous across edges, so the proxy is too. That line is also the contact normal.
  const Vec3 direction = sub(centre, hit.point);
  const double length = norm(direction);
  if (length > 1e-3 * params_.radius && dot(direction, hit.normal) > 0.0)
    hit.normal = scaled(direction, 1.0 / length);
  return add_scaled(hit.point, hit.normal, params_.radius + params_.skin);
}

void GodObjectProxy::update(const SurfaceQuery& world, const Vec3& device_position,
                            const Vec3& device_velocity) noexcept {
  if (!is_finite(device_position)) return;  // keep the last proxy; the engine zeroes the force
  if (!in_contact_) {
    SurfaceHit hit;
    double signed_distance = 0.0;
    if (world.first_hit(position_, device_position, params_.radius, hit)) {
      position_ =
          on_surface(hit, add_scaled(position_, sub(device_position, position_), hit.fraction));
      contact_ = hit;
      in_contact_ = true;
    } else if (!world.clear_of(device_position, params_.radius) &&
               world.closest_point(device_position, params_.inside_search, hit, signed_distance) &&
               signed_distance < params_.radius) {
      // Overlapping without a sweep hit: a surface came onto the device, or it started inside.
      position_ = on_surface(hit, device_position);
      contact_ = hit;
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
      position_ = on_surface(hit, add_scaled(position_, sub(device, position_), hit.fraction));
      contact_ = hit;
      continue;
    }
    // Slide on the tangent plane toward the device's projection on it.
    const Vec3 goal = add_scaled(device, n, -normal_part);  // at the proxy's height
    const Vec3 start = position_;
    if (world.first_hit(position_, goal, params_.radius, hit)) {
      position_ = on_surface(hit, add_scaled(position_, sub(goal, position_), hit.fraction));
      contact_ = hit;
      continue;
    }
    position_ = goal;
    // A curved surface falls away from the tangent plane: put the proxy back on it.
    double signed_distance = 0.0;
    if (world.closest_point(position_, params_.inside_search + params_.radius, hit,
                            signed_distance)) {
      position_ = on_surface(hit, position_);
      contact_ = hit;
    }
    const Vec3 moved = sub(position_, start);
    if (dot(moved, moved) < 1e-24) break;  // converged (1e-12 m)
  }
  return true;
}

}  // namespace tacta::haptics
