// The per-tick haptic chain as the engine runs it, for tests: proxy, first-contact limiter,
// virtual coupling, passivity controller, force limiter, then the device (a SimulatedHand).
#pragma once

#include <algorithm>

#include "simulated_hand.hpp"
#include "tacta/haptics/first_contact.hpp"
#include "tacta/haptics/force_limiter.hpp"
#include "tacta/haptics/god_object.hpp"
#include "tacta/haptics/passivity.hpp"
#include "tacta/haptics/virtual_coupling.hpp"

namespace tacta::haptics::testing {

struct ChainOptions {
  VirtualCouplingParams coupling{1000.0, 0.0};
  bool first_contact = true;
  FirstContactParams first_contact_params{};
  bool passivity = true;
  double peak_force = 3.3;  // N
  double dt = 1e-3;         // s
};

struct ChainStats {
  double peak_force = 0.0;          // N, largest force sent
  double last_force = 0.0;          // N, magnitude at the end
  // J: the hand's energy (kinetic plus hand spring). With an undamped hand and a fixed target it
  // changes only by the work the rendered force does, so a rise above the start is energy the
  // rendering injected (the observer's E is exactly that work with the opposite sign).
  double peak_energy = 0.0;         // J, largest after settle_time
  double final_energy = 0.0;        // J
  double worst_deficit = 0.0;       // J, passivity observer's worst negative energy
  double first_contact_time = -1.0; // s
};

inline ChainStats run_chain(SimulatedHand& hand, const SurfaceQuery& world, const ChainOptions& options,
                            double duration, double settle_time = 0.0) {
  GodObjectProxy proxy;
  FirstContactLimiter onset(options.first_contact_params);
  VirtualCoupling coupling(options.coupling);
  PassivityParams pp;
  pp.controller_enabled = options.passivity;
  PassivityController passivity(pp);
  ForceLimiter limiter(options.peak_force);
  proxy.reset(hand.position);
  passivity.reset(hand.position);
  ChainStats stats;
  const int ticks = static_cast<int>(duration / options.dt + 0.5);
  for (int n = 0; n < ticks; ++n) {
    proxy.update(world, hand.position, hand.velocity);
    if (proxy.in_contact() && stats.first_contact_time < 0.0) stats.first_contact_time = hand.time;
    Vec3 stretch = sub(proxy.position(), hand.position);
    if (options.first_contact) stretch = onset.shape(stretch, proxy.in_contact(), options.dt);
    Vec3 force = coupling.force(stretch, sub(proxy.velocity(), hand.velocity));
    force = passivity.update(hand.position, hand.velocity, options.dt, force);
    force = limiter.limit(force);
    passivity.record_sent(force);
    stats.peak_force = std::max(stats.peak_force, norm(force));
    stats.last_force = norm(force);
    hand.step(options.dt, force);
    const double energy = hand.energy();
    if (hand.time >= settle_time) stats.peak_energy = std::max(stats.peak_energy, energy);
    stats.final_energy = energy;
  }
  stats.worst_deficit = passivity.worst_energy_deficit();
  return stats;
}

}  // namespace tacta::haptics::testing
