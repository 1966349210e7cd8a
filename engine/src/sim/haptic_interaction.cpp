#include "haptic_interaction.hpp"

#include <algorithm>

namespace tacta {

using haptics::scaled;
using haptics::sub;

HapticInteraction::HapticInteraction(World& world, CollisionContext& collision) : collision_(collision) {
  channels_.reserve(world.device_count());
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceSlot& slot = world.device(d);
    haptics::GodObjectParams proxy;
    proxy.radius = slot.desc.tool.radius;
    haptics::VirtualCouplingParams coupling;
    coupling.stiffness = slot.desc.coupling_stiffness;
    coupling.damping = slot.desc.coupling_damping;
    channels_.push_back(Channel{haptics::GodObjectProxy(proxy), haptics::VirtualCoupling(coupling),
                                haptics::FirstContactLimiter(), haptics::PassivityController(),
                                haptics::ForceLimiter(slot.device->capabilities().peak_force), false});
  }
}

void HapticInteraction::before_step(World& world, double time, double dt) noexcept {
  collision_.refit(time, dt);
  for (size_t d = 0; d < world.device_count(); ++d) {
    DeviceSlot& slot = world.device(d);
    Channel& ch = channels_[d];
    const Vec3 device{slot.sample.position[0], slot.sample.position[1], slot.sample.position[2]};
    const Vec3 velocity{slot.sample.velocity[0], slot.sample.velocity[1], slot.sample.velocity[2]};
    tacta_collision_shape& tool = collision_.tool(d);
    if (!ch.started) {
      ch.proxy.reset(device);
      ch.passivity.reset(device);
      ch.started = true;
    }
    // What the device actually rendered last tick (zero after a fault) feeds the observer.
    ch.passivity.record_sent(slot.force);
    if (slot.state != TACTA_DEVICE_CONNECTED) {
      slot.force = {0, 0, 0};
      slot.in_contact = false;
      continue;
    }
    for (int a = 0; a < 3; ++a) tool.pose_start.position[a] = ch.proxy.position()[static_cast<size_t>(a)];
    ch.proxy.update(collision_.surface_query(slot.touched_body), device, velocity);
    const Vec3& proxy = ch.proxy.position();
    for (int a = 0; a < 3; ++a) tool.pose_end.position[a] = proxy[static_cast<size_t>(a)];
    const bool contact = ch.proxy.in_contact();
    const Vec3 stretch = ch.first_contact.shape(sub(proxy, device), contact, dt);
    const Vec3 relative = sub(ch.proxy.velocity(), velocity);
    const Vec3 desired = contact ? ch.coupling.force(stretch, relative) : Vec3{0, 0, 0};
    const Vec3 passive = ch.passivity.update(device, velocity, dt, desired);
    const Vec3 sent = ch.limiter.limit(passive);
    slot.force = sent;
    slot.proxy = proxy;
    slot.in_contact = contact;
    slot.stats.energy_injected_J = ch.passivity.worst_energy_deficit();
    if (contact) apply_reaction(world, ch.proxy.contact(), scaled(sent, -1.0));
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
