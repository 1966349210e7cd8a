#include "tacta/haptics/contact_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tacta::haptics {

ContactRenderer::ContactRenderer(const ContactRendererParams& params) noexcept
    : params_(params),
      proxy_(params.proxy),
      onset_(params.first_contact),
      coupling_(params.coupling),
      passivity_(params.passivity),
      limiter_(params.peak_force) {
  stats_.force_limit = limiter_.peak_force();
}

void ContactRenderer::reset(const Vec3& device_position) noexcept {
  proxy_.reset(device_position);
  onset_.reset();
  passivity_.reset(device_position);
  stats_ = {};
  stats_.force_limit = limiter_.peak_force();
  steady_sum_ = 0.0;
  steady_count_ = 0;
  last_stretch_ = last_sent_ = {0.0, 0.0, 0.0};
  coupling_energy_ = 0.0;
  was_in_contact_ = false;
}

double ContactRenderer::onset_budget(const Vec3& stretch) noexcept {
  // The coupling's two-port ledger: the force held over the last tick times the change of the
  // stretch proxy - device over it is exactly the energy the coupling took from the device
  // (device moving in) and from the body (surface moving out, pushing the proxy).
  if (!was_in_contact_)
    coupling_energy_ = coupling_.spring_energy(stretch);  // the penetration the contact began with
  else
    coupling_energy_ += dot(last_sent_, sub(stretch, last_stretch_));
  last_stretch_ = stretch;
  const double k = coupling_.params().stiffness;
  if (!(k > 0.0)) return std::numeric_limits<double>::infinity();
  return std::sqrt(2.0 * std::max(coupling_energy_, 0.0) / k);
}

ContactRendering ContactRenderer::tick(const SurfaceQuery& world, double time,
                                       const Vec3& device_position, const Vec3& device_velocity,
                                       double dt) noexcept {
  move_proxy(world, device_position, device_velocity);
  return couple(time, device_position, device_velocity, dt);
}

void ContactRenderer::move_proxy(const SurfaceQuery& world, const Vec3& device_position,
                                 const Vec3& device_velocity) noexcept {
  sample_finite_ = is_finite(device_position) && is_finite(device_velocity);
  if (sample_finite_) proxy_.update(world, device_position, device_velocity);
}

ContactRendering ContactRenderer::couple(double time, const Vec3& device_position,
                                         const Vec3& device_velocity, double dt) noexcept {
  ContactRendering out;
  if (!sample_finite_) {
    ++stats_.non_finite_forces;  // a bad sample: zero force this tick
    passivity_.record_sent(out.device_force);
    last_sent_ = out.device_force;
    update_stats(time, 0.0);
    return out;
  }
  out.in_contact = proxy_.in_contact();
  Vec3 desired{0.0, 0.0, 0.0};
  if (out.in_contact) {
    out.contact = proxy_.contact();
    Vec3 stretch = sub(proxy_.position(), device_position);
    stretch = yield_stretch(stretch, coupling_.params().stiffness, local_);
    const double budget = onset_budget(stretch);
    if (params_.first_contact_enabled) stretch = onset_.shape(stretch, true, dt, budget);
    desired = coupling_.force(stretch, sub(proxy_.velocity(), device_velocity));
    // The coupling damper acts on the relative velocity: a device leaving fast while the spring
    // is nearly relaxed would be pulled back onto the surface (0.057 N at the liver demo's third
    // release, 1 N s/m at 0.06 m/s). A contact only pushes: no component into the surface.
    const double along_normal = dot(desired, out.contact.normal);
    if (along_normal < 0.0) desired = add_scaled(desired, out.contact.normal, -along_normal);
  } else {
    onset_.shape({0.0, 0.0, 0.0}, false, dt);  // re-arm for the next contact
  }
  // The observer runs every tick (the device moves under the held force in free space too); the
  // controller only adds damping in contact.
  Vec3 passive = passivity_.update(device_position, device_velocity, dt, desired, out.in_contact);
  // A contact pushes; it never pulls or drags sideways. The passivity damper opposes the device's
  // velocity, which is right while it only weakens the coupling force, but on release (device
  // moving out) a full damper force would stick the stylus to the surface (seen as -0.9 N spikes
  // in the liver demo). So in contact the controller may only scale the coupling force down
  // along its own direction, to zero at most: the part of its damper along that force is kept,
  // the rest is dropped.
  if (out.in_contact) {
    const double desired2 = dot(desired, desired);
    double scale = 1.0;
    if (desired2 > 0.0) scale = std::clamp(dot(passive, desired) / desired2, 0.0, 1.0);
    passive = scaled(desired, desired2 > 0.0 ? scale : 0.0);
  }
  ForceLimitResult result = ForceLimitResult::unchanged;
  out.device_force = limiter_.limit(passive, &result);
  if (result == ForceLimitResult::scaled) ++stats_.limited_forces;
  if (result == ForceLimitResult::non_finite_zeroed) ++stats_.non_finite_forces;
  passivity_.record_sent(out.device_force);
  last_sent_ = out.device_force;
  was_in_contact_ = out.in_contact;
  out.body_reaction = scaled(out.device_force, -1.0);
  if (out.in_contact && stats_.first_contact_time < 0.0) stats_.first_contact_time = time;
  update_stats(time, norm(out.device_force));
  return out;
}

void ContactRenderer::update_stats(double time, double force) noexcept {
  stats_.max_force = std::max(stats_.max_force, force);
  stats_.energy_injected = passivity_.worst_energy_deficit();
  if (stats_.first_contact_time < 0.0) return;
  const double since = time - stats_.first_contact_time;
  const ContactStatsParams& p = params_.stats;
  if (since <= p.onset_window)
    stats_.first_contact_peak = std::max(stats_.first_contact_peak, force);
  if (since >= p.settle_delay && since < p.settle_delay + p.steady_window) {
    steady_sum_ += force;
    ++steady_count_;
    stats_.steady_contact = steady_sum_ / static_cast<double>(steady_count_);
  }
}

}  // namespace tacta::haptics
