// Runs the engine's ContactRenderer against a SimulatedHand, as the haptic task would: read the
// device, render, hold the force for one tick.
#pragma once

#include <algorithm>

#include "simulated_hand.hpp"
#include "tacta/haptics/contact_renderer.hpp"

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
  double peak_force = 0.0;  // N, largest force sent
  double last_force = 0.0;  // N, magnitude at the end
  // J: the hand's energy (kinetic plus hand spring). With an undamped hand and a fixed target it
  // changes only by the work the rendered force does, so a rise above the start is energy the
  // rendering injected (the observer's E is exactly that work with the opposite sign).
  double peak_energy = 0.0;    // J, largest after settle_time
  double final_energy = 0.0;   // J
  double worst_deficit = 0.0;  // J, passivity observer's worst negative energy
  ContactStats renderer{};     // the renderer's own report numbers
};

inline ContactRendererParams renderer_params(const ChainOptions& options) {
  ContactRendererParams p;
  p.coupling = options.coupling;
  p.first_contact_enabled = options.first_contact;
  p.first_contact = options.first_contact_params;
  p.passivity.controller_enabled = options.passivity;
  p.peak_force = options.peak_force;
  return p;
}

inline ChainStats run_chain(SimulatedHand& hand, const SurfaceQuery& world,
                            const ChainOptions& options, double duration,
                            double settle_time = 0.0) {
  ContactRenderer renderer(renderer_params(options));
  renderer.reset(hand.position);
  ChainStats stats;
  const int ticks = static_cast<int>(duration / options.dt + 0.5);
  for (int n = 0; n < ticks; ++n) {
    const ContactRendering r =
        renderer.tick(world, hand.time, hand.position, hand.velocity, options.dt);
    stats.peak_force = std::max(stats.peak_force, norm(r.device_force));
    stats.last_force = norm(r.device_force);
    hand.step(options.dt, r.device_force);
    const double energy = hand.energy();
    if (hand.time >= settle_time) stats.peak_energy = std::max(stats.peak_energy, energy);
    stats.final_energy = energy;
  }
  stats.worst_deficit = renderer.passivity().worst_energy_deficit();
  stats.renderer = renderer.stats();
  return stats;
}

}  // namespace tacta::haptics::testing
