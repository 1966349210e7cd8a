#include "haptic_interaction.hpp"

#include <algorithm>

namespace tacta {

HapticInteraction::HapticInteraction(World& world, CollisionContext& collision) : collision_(collision) {
  channels_.reserve(world.device_count());
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceSlot& slot = world.device(d);
    haptics::ContactRendererParams params;
    params.proxy.radius = slot.desc.tool.radius;
    params.coupling.stiffness = slot.desc.coupling_stiffness;
    params.coupling.damping = slot.desc.coupling_damping;
    params.passivity.controller_enabled = slot.desc.coupling_passivity;
    params.first_contact_enabled = slot.desc.coupling_first_contact;
    params.peak_force = slot.device->capabilities().peak_force;
    channels_.push_back(Channel{haptics::ContactRenderer(params), false});
  }
}

void HapticInteraction::before_step(World& world, double time, double dt) noexcept {
  collision_.refit(time, dt);
  for (size_t d = 0; d < world.device_count(); ++d) {
    DeviceSlot& slot = world.device(d);
    Channel& ch = channels_[d];
    const Vec3 device{slot.sample.position[0], slot.sample.position[1], slot.sample.position[2]};
    const Vec3 velocity{slot.sample.velocity[0], slot.sample.velocity[1], slot.sample.velocity[2]};
    if (!ch.started) {
      ch.renderer.reset(device);
      ch.started = true;
    }
    if (slot.state != TACTA_DEVICE_CONNECTED) {
      slot.force = {0, 0, 0};
      slot.in_contact = false;
      continue;
    }
    tacta_collision_shape& tool = collision_.tool(d);
    for (int a = 0; a < 3; ++a) tool.pose_start.position[a] = slot.proxy[static_cast<size_t>(a)];
    const haptics::ContactRendering out =
        ch.renderer.tick(collision_.surface_query(slot.touched_body), time, device, velocity, dt);
    slot.proxy = ch.renderer.proxy().position();
    for (int a = 0; a < 3; ++a) tool.pose_end.position[a] = slot.proxy[static_cast<size_t>(a)];
    slot.force = out.device_force;
    slot.in_contact = out.in_contact;
    const haptics::ContactStats& st = ch.renderer.stats();
    slot.stats.first_contact_peak_N = st.first_contact_peak;
    slot.stats.steady_contact_N = st.steady_contact;
    slot.stats.energy_injected_J = st.energy_injected;
    slot.stats.first_contact_time_s = st.first_contact_time;
    if (out.in_contact) apply_reaction(world, out.contact, out.body_reaction);
  }
}

void HapticInteraction::apply_reaction(World& world, const haptics::SurfaceHit& hit, const Vec3& force) noexcept {
  if (hit.body < 0 || static_cast<size_t>(hit.body) >= world.body_count() || hit.triangle < 0) return;
  SoftBody& body = world.body(static_cast<size_t>(hit.body));
  const std::vector<uint32_t>& triangles = body.topology->mesh.triangles;
  const auto t = static_cast<size_t>(hit.triangle);
  if (3 * t + 2 >= triangles.size()) return;
  // Barycentric weights of the touched point; a hit without them spreads the force evenly.
  const double sum = hit.barycentric[0] + hit.barycentric[1] + hit.barycentric[2];
  for (int k = 0; k < 3; ++k) {
    const uint32_t node = triangles[3 * t + static_cast<size_t>(k)];
    const double w = sum > 0 ? hit.barycentric[k] / sum : 1.0 / 3.0;
    for (int a = 0; a < 3; ++a) body.contact_forces[3 * node + static_cast<size_t>(a)] += w * force[static_cast<size_t>(a)];
  }
}

void HapticInteraction::after_step(World&, double, double) noexcept {}

void CollisionResponse::after_step(World&, double time, double dt) noexcept {
  bits_ |= collision_.detect_and_respond(time, dt);
  contacts_total_ += collision_.contact_count();
}

}  // namespace tacta
