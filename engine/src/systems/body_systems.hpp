// The haptic task's body systems: free functions over views of the bodies in the scene (entity
// index = body slot). HapticLoop::tick calls them in the tick's order. Each runs on the tick's
// thread and allocates nothing, takes no lock, throws nothing.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "output/recorders.hpp"
#include "systems/body_step.hpp"
#include "systems/body_worker.hpp"
#include "systems/tick_events.hpp"
#include "world/world.hpp"

namespace tacta {

// Each body's contact sum starts the tick at its applied loads (stepping API), else zero.
void start_contact_sums(World& world) noexcept;

// Scheduled swaps due by `time` and a swap posted in the body's mailbox take effect. Bodies on a
// worker thread are skipped here: step_bodies swaps them between two of their steps.
void take_model_swaps(World& world, double time) noexcept;

// One model step for every body in the scene that is due (every tick, its own rate, or its
// worker's boundary; `workers` per slot, null for haptic-thread bodies). False when a body
// faulted this tick.
bool step_bodies(World& world, const std::vector<std::unique_ptr<BodyWorker>>& workers,
                 TickEvents& events, double time, double dt) noexcept;

// Trajectories of the recorded nodes and the probes' positions at `time`.
void record_bodies(World& world, double time, Recorder<TrajectoryRow>& trajectory,
                   Recorder<ProbeRow>& probes) noexcept;

}  // namespace tacta
