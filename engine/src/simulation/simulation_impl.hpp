// The inside of a Simulation, shared by its two source files: simulation.cpp (building, swaps,
// batch runs) and simulation_state.cpp (stepping, state access, the report so far).
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "collision/collision_context.hpp"
#include "haptic_interaction/haptic_interaction.hpp"
#include "plugin/complete_params.hpp"
#include "simulation/realtime_cuts.hpp"
#include "systems/haptic_loop.hpp"
#include "tacta/sim/simulation.hpp"
#include "timing/clock_session.hpp"
#include "world/world.hpp"

namespace tacta {

// The cuts a scene makes as it runs (simulation_cut.cpp): its cut events, and what the devices'
// blades swept (each blade's sweep is cut `interval` after it began, and when its button is let
// go). Lockstep runs make them between ticks (run_due); realtime runs through RealtimeCuts, which
// asks what is due here.
class SceneCuts final : public BetweenTicks {
 public:
  using Cut = std::function<CutSummary(size_t slot, std::span<const double>, CutMode)>;
  // Checks every event's body can be cut (InputError at the event otherwise); `cut` makes one.
  SceneCuts(World& world, Cut cut);
  double next_due_s() const noexcept override;
  void run_due(double time) override;
  // A restored run: the events due by `time` (s) were the saved run's.
  void skip_past(double time) noexcept;

  // The next event when it is due by `time` (s, to half a tick), else null; pass_event moves on.
  const BodyEventDesc* due_event(double time) const noexcept;
  void pass_event() noexcept { ++next_; }
  // Whether `blade`'s sweep is due by `time` (s, to half a tick).
  bool sweep_due(const BladeSweep& blade, double time) const noexcept;
  // Whether a sweep of device `device`'s blade cuts body `slot` (the body it `touches`, else
  // every body whose model takes topology edits).
  bool sweep_cuts(size_t device, size_t slot) const noexcept;

 private:
  void cut_sweep(size_t device, BladeSweep& blade);
  World& world_;
  Cut cut_;
  std::vector<const BodyEventDesc*> events_;  // by time
  size_t next_ = 0;
};

struct Simulation::Impl {
  Impl(const SceneDesc& scene, const PluginRegistry& registry)
      : world(scene, registry), plugins(registry), salt(next_salt()) {
    // Collision is needed for contact response, and for the haptic proxy's surface queries.
    if (scene.collision.enabled || world.device_count() > 0) {
      collision = std::make_unique<CollisionContext>(world, registry);
      if (world.device_count() > 0)
        haptics = std::make_unique<HapticInteraction>(world, *collision);
      if (scene.collision.enabled) response = std::make_unique<CollisionResponse>(*collision);
    }
    scene_cuts =
        std::make_unique<SceneCuts>(world, [this](size_t slot, std::span<const double> blade,
                                                  CutMode mode) { return cut(slot, blade, mode); });
  }
  World world;
  const PluginRegistry& plugins;
  std::atomic<bool> stop{false};
  std::vector<std::string> requested_models;  // per body, for body_model()
  std::vector<ParamSet> requested_params;     // per body, for body_params() and set_param swaps
  std::atomic<bool> running{false};           // run() is on: set_param cannot reach the model live
  std::unique_ptr<CollisionContext> collision;
  std::unique_ptr<HapticInteraction> haptics;
  std::unique_ptr<CollisionResponse> response;
  std::unique_ptr<ClockSession> clock;        // built at the first step or run
  std::vector<std::string> checkpoint_notes;  // what the last save or restore could not carry
  std::unique_ptr<SceneCuts> scene_cuts;
  std::unique_ptr<RealtimeCuts> realtime_cuts;  // with the clock: cuts in realtime runs

  ClockSession& session() {
    if (!clock) {
      clock = std::make_unique<ClockSession>(world, haptics.get(), response.get());
      clock->set_between_ticks(scene_cuts.get());
      realtime_cuts = std::make_unique<RealtimeCuts>(world, *scene_cuts, collision.get(),
                                                     haptics.get(), *clock);
      clock->set_at_tick_boundary(realtime_cuts.get());
    }
    return *clock;
  }
  RunResult collect(const ScheduleResult& schedule) const;
  // Cuts body `slot` and brings collision, haptics and rendering up to date (simulation_cut.cpp).
  CutSummary cut(size_t slot, std::span<const double> triangles, CutMode mode);
  static uint32_t next_salt() noexcept;
  // Handles: a body's generation is the world's XOR this Simulation's salt, a device's is the
  // salt, so a handle from another Simulation fails the check (simulation_handles.cpp).
  const uint32_t salt;
  BodyHandle handle_of(ecs::Entity body) const noexcept {
    return {body.index, body.generation ^ salt};
  }
  ecs::Entity entity_of(BodyHandle body) const noexcept {
    return {body.index, body.generation ^ salt};
  }
  BodyHandle body_handle(size_t index) const { return handle_of(world.body_handle(index)); }
  DeviceHandle device_handle(size_t index) const noexcept {
    return {static_cast<uint32_t>(index), salt};
  }
  // The index a handle names; InputError naming the handle and why it is stale or foreign.
  size_t body_at(BodyHandle body) const;
  size_t device_at(DeviceHandle device) const;
};

// Writes report.json, the CSV records and the plots of everything since open into `dir`.
void write_outputs_into(const std::string& dir, const HapticLoop& loop, const World& world,
                        RunResult& result);

}  // namespace tacta
