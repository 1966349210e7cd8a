#include "haptic_interaction/haptic_interaction.hpp"

#include <algorithm>
#include <array>
#include <chrono>

#include "tacta/vec3.hpp"

namespace tacta {

namespace {

haptics::ContactRendererParams renderer_params(const DeviceComponents& dev, double proxy_radius) {
  haptics::ContactRendererParams params;
  params.proxy.radius = proxy_radius;
  params.coupling.stiffness = dev.link.desc.coupling_stiffness;
  params.coupling.damping = dev.link.desc.coupling_damping;
  params.passivity.controller_enabled = dev.link.desc.coupling_passivity;
  params.first_contact_enabled = dev.link.desc.coupling_first_contact;
  params.peak_force = dev.link.device->capabilities().peak_force;
  return params;
}

}  // namespace

HapticInteraction::HapticInteraction(World& world, CollisionContext& collision)
    : collision_(collision) {
  channels_.reserve(world.device_count());
  for (size_t d = 0; d < world.device_count(); ++d) {
    const Tool& tool = world.tool(d);
    channels_.push_back(
        Channel{haptics::ContactRenderer(renderer_params(world.device(d), tool.proxy_radius)),
                false, LocalModel{}, tool.revision});
  }
}

void HapticInteraction::update_tools(World& world) noexcept {
  tools_start_ = std::chrono::steady_clock::now();
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceComponents dev = world.device(d);
    Channel& ch = channels_[d];
    ch.rendering = false;
    if (const Tool& t = world.tool(d); t.revision != ch.tool_revision) {
      // A new tool: the proxy takes its radius and starts afresh where the device is, as after a
      // reconnection (no stored stretch is carried across the change).
      ch.renderer = haptics::ContactRenderer(renderer_params(dev, t.proxy_radius));
      ch.started = false;
      ch.tool_revision = t.revision;
    }
    ch.device = {dev.link.sample.position[0], dev.link.sample.position[1],
                 dev.link.sample.position[2]};
    ch.velocity = {dev.link.sample.velocity[0], dev.link.sample.velocity[1],
                   dev.link.sample.velocity[2]};
    if (!ch.started) {
      ch.renderer.reset(ch.device);
      ch.started = true;
      // The tool starts where the proxy does: from the default origin, its first sweep would cut
      // through whatever lies between (contacts tens of mm deep for the collision response).
      dev.contact.proxy = ch.renderer.proxy().position();
    }
    // A tool whose body was removed has nothing to touch: no force, and a fresh start if the
    // device goes on (its proxy would otherwise stay on a surface that is gone).
    const bool body_gone = dev.contact.touched_body >= 0 &&
                           !world.body_present(static_cast<size_t>(dev.contact.touched_body));
    if (dev.link.state != TACTA_DEVICE_CONNECTED || body_gone) {
      dev.contact.force = {0, 0, 0};
      dev.contact.in_contact = false;
      ch.started =
          false;  // a device that comes back starts afresh where it is (no jump, no stored energy)
      continue;
    }
    ch.rendering = true;
    tacta_collision_shape& tool = collision_.tool(d);
    for (int a = 0; a < 3; ++a)
      tool.pose_start.position[a] = dev.contact.proxy[static_cast<size_t>(a)];
    prepare_local_model(world, ch, dev);
  }
}

void HapticInteraction::refit_surfaces(double time, double dt) noexcept {
  refit_start_ = std::chrono::steady_clock::now();
  collision_.refit_for_proxy(time, dt);
  refit_end_ = std::chrono::steady_clock::now();
}

void HapticInteraction::move_proxies(World& world) noexcept {
  for (size_t d = 0; d < world.device_count(); ++d) {
    Channel& ch = channels_[d];
    if (!ch.rendering) continue;
    ch.renderer.move_proxy(collision_.surface_query(world.device(d).contact.touched_body, d),
                           ch.device, ch.velocity);
  }
}

void HapticInteraction::couple(World& world, double time, double dt) noexcept {
  for (size_t d = 0; d < world.device_count(); ++d) {
    Channel& ch = channels_[d];
    if (!ch.rendering) continue;
    const DeviceComponents dev = world.device(d);
    const haptics::ContactRendering out = ch.renderer.couple(time, ch.device, ch.velocity, dt);
    follow_local_model(world, ch, out, dt);
    dev.contact.proxy = ch.renderer.proxy().position();
    tacta_collision_shape& tool = collision_.tool(d);
    for (int a = 0; a < 3; ++a)
      tool.pose_end.position[a] = dev.contact.proxy[static_cast<size_t>(a)];
    dev.contact.force = out.device_force;
    dev.contact.in_contact = out.in_contact;
    const haptics::ContactStats& st = ch.renderer.stats();
    dev.stats.first_contact_peak_N = st.first_contact_peak;
    dev.stats.steady_contact_N = st.steady_contact;
    dev.stats.energy_injected_J = st.energy_injected;
    dev.stats.first_contact_time_s = st.first_contact_time;
    if (out.in_contact) apply_reaction(world, out.contact, out.body_reaction);
  }
  collision_bits_ = collision_.take_bits();
  // The queries' time includes the embedded vertices they brought up to date (the patch).
  const auto ms = [](auto a, auto b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
  };
  const double render_ms =
      ms(tools_start_, refit_start_) + ms(refit_end_, std::chrono::steady_clock::now());
  parts_.surface_update = ms(refit_start_, refit_end_) + collision_.patch_ms();
  parts_.proxy_query = collision_.query_ms() - collision_.patch_ms();
  parts_.coupling = render_ms - collision_.query_ms();
}

namespace {

// Normalised barycentric weights of a touched point; a hit without them gets equal thirds.
std::array<double, 3> touch_weights(const double* barycentric) noexcept {
  const double sum = barycentric[0] + barycentric[1] + barycentric[2];
  if (!(sum > 0)) return {1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0};
  return {barycentric[0] / sum, barycentric[1] / sum, barycentric[2] / sum};
}

// Where the point with those weights on `triangle` of the body is, in `positions` (m).
Vec3 point_on_triangle(const SoftBody& body, const std::vector<double>& positions, int triangle,
                       const double* barycentric) noexcept {
  if (body.surface.mesh)
    return surface_point(*body.surface.mesh, static_cast<uint32_t>(triangle), barycentric,
                         positions.data());
  const std::vector<uint32_t>& tris = body.shape.topology->mesh.triangles;
  const std::array<double, 3> w = touch_weights(barycentric);
  Vec3 p{0, 0, 0};
  for (size_t k = 0; k < 3; ++k) {
    const uint32_t n = tris[3 * static_cast<size_t>(triangle) + k];
    for (size_t a = 0; a < 3; ++a) p[a] += w[k] * positions[3 * n + a];
  }
  return p;
}

}  // namespace

void HapticInteraction::apply_reaction(World& world, const haptics::SurfaceHit& hit,
                                       const Vec3& force) noexcept {
  if (hit.body < 0 || static_cast<size_t>(hit.body) >= world.body_count() || hit.triangle < 0)
    return;
  const SoftBody body = world.body(static_cast<size_t>(hit.body));
  if (!body.present()) return;
  const std::vector<uint32_t>& triangles =
      body.surface.mesh ? body.surface.mesh->triangles : body.shape.topology->mesh.triangles;
  const auto t = static_cast<size_t>(hit.triangle);
  if (3 * t + 2 >= triangles.size()) return;
  // The reaction goes to the touched triangle's vertices by the touched point's weights; an
  // embedded surface's vertices pass their share on to their tet's nodes by the same rule.
  const std::array<double, 3> w = touch_weights(hit.barycentric);
  for (size_t k = 0; k < 3; ++k) {
    const double share[3] = {w[k] * force[0], w[k] * force[1], w[k] * force[2]};
    if (body.surface.mesh) {
      spread_to_nodes(*body.surface.mesh, triangles[3 * t + k], share,
                      body.loads.contact_forces.data());
      continue;
    }
    for (size_t a = 0; a < 3; ++a)
      body.loads.contact_forces[3 * triangles[3 * t + k] + a] += share[a];
  }
}

void HapticInteraction::prepare_local_model(World& world, Channel& ch,
                                            const DeviceComponents& dev) noexcept {
  LocalModel& m = ch.local;
  const int touched = m.body >= 0 ? m.body : dev.contact.touched_body;
  if (touched < 0 || static_cast<size_t>(touched) >= world.body_count() ||
      !world.body(static_cast<size_t>(touched)).settings.own_thread) {
    ch.renderer.set_local_compliance({});
    return;
  }
  const SoftBody body = world.body(static_cast<size_t>(touched));
  if (m.body != touched) {
    m = LocalModel{};
    m.body = touched;
    m.refreshes_seen = body.progress.refreshes;
  }
  if (body.progress.refreshes != m.refreshes_seen) {
    // The worker finished a step and took the next: the state now shown felt `posted`, the step
    // now running is driven by the mean of the ticks since (BodyWorker::post does the same sums).
    m.refreshes_seen = body.progress.refreshes;
    m.felt = m.posted;
    m.posted = m.impulse_time > 0 ? scaled(m.impulse, 1.0 / m.impulse_time) : Vec3{0, 0, 0};
    m.impulse = {0, 0, 0};
    m.impulse_time = 0;
    if (m.pressing) {
      // The refresh moved the touched point (collect() kept the previous state in
      // step_start): the proxy moves with it.
      const Vec3 before = point_on_triangle(body, body.nodes.step_start, m.triangle, m.barycentric);
      const Vec3 after = point_on_triangle(body, body.nodes.positions, m.triangle, m.barycentric);
      ch.renderer.carry_proxy(sub(after, before));
      // Secant point stiffness: the normal force the state felt over how far the pressed material
      // point has gone in since the contact began; smoothed, since one step is not a static state.
      const Vec3 now =
          point_on_triangle(body, body.nodes.positions, m.onset_triangle, m.onset_barycentric);
      const double depth = dot(sub(m.onset_point, now), m.onset_normal);  // m
      const double force = dot(m.felt, m.onset_normal);                   // N
      if (depth > 1e-4 && force > 0.02) {
        const double measured = force / depth;  // N/m
        m.stiffness = m.stiffness > 0 ? 0.5 * m.stiffness + 0.5 * measured : measured;
      }
    }
  }
  haptics::LocalCompliance c;
  // Until the body has shown its stiffness (the first refresh of a press) the surface is rendered
  // as the last step left it (an analytic guess, a flat punch on a half-space, is 3 to 4 times
  // softer than the meshes' own response: the force would jump when the measurement came).
  c.active = body.settings.local_contact_yielding && m.stiffness > 0;
  // Why the measured stiffness matters: the surface the loop sees lags the force it renders by
  // two periods (the step posted at k runs on the forces of k-2..k-1 and shows at k+1). With the
  // device still, F_k = const + g F_(k-2) with g = k_c (k_true - k_l) / (k_true (k_l + k_c)): the
  // rigid snapshot (k_l -> infinity) gives g = -k_c / k_true, a ringing or bouncing contact as soon
  // as the coupling is stiffer than the tissue; k_l near k_true gives g near 0. Whatever k_l, the
  // held force is the exact series k_c k_true / (k_c + k_true) d.
  c.stiffness = m.stiffness;
  c.normal = m.onset_normal;
  c.reference_force = std::max(0.0, dot(m.felt, m.onset_normal));
  ch.renderer.set_local_compliance(c);
}

void HapticInteraction::follow_local_model(World& world, Channel& ch,
                                           const haptics::ContactRendering& out,
                                           double dt) noexcept {
  LocalModel& m = ch.local;
  if (m.body < 0) return;
  m.impulse = add_scaled(m.impulse, out.device_force, dt);
  m.impulse_time += dt;
  if (!out.in_contact || out.contact.body != m.body || out.contact.triangle < 0) {
    m.pressing = false;
    return;
  }
  m.triangle = out.contact.triangle;
  for (int k = 0; k < 3; ++k) m.barycentric[k] = out.contact.barycentric[k];
  if (!m.pressing) {
    m.pressing = true;
    m.onset_triangle = out.contact.triangle;
    for (int k = 0; k < 3; ++k) m.onset_barycentric[k] = out.contact.barycentric[k];
    m.onset_point = point_on_triangle(world.body(static_cast<size_t>(m.body)),
                                      world.body(static_cast<size_t>(m.body)).nodes.positions,
                                      m.onset_triangle, m.onset_barycentric);
    m.onset_normal = out.contact.normal;
  }
}

void HapticInteraction::after_write(World& world) noexcept {
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceComponents dev = world.device(d);
    channels_[d].renderer.override_sent(
        {dev.contact.force[0], dev.contact.force[1], dev.contact.force[2]});
  }
}

uint32_t CollisionResponse::respond(double time, double dt) noexcept {
  const uint32_t bits = collision_.detect_and_respond(time, dt) | collision_.take_bits();
  bits_ |= bits;
  contacts_total_ += collision_.contact_count();
  return bits;
}

void HapticInteraction::surface_changed(World& world, size_t body) noexcept {
  for (size_t d = 0; d < channels_.size(); ++d)
    if (world.device(d).contact.touched_body == static_cast<int>(body))
      channels_[d].renderer.surface_changed();
}

}  // namespace tacta
