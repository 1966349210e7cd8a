// The world of one run: an ECS registry with an entity per body slot and per device, built from
// a validated scene. Building either completes or throws InputError; nothing is left
// half-loaded. Bodies can be added and removed while the scene runs: a request (any thread but
// the tick's) builds what it needs, claims a reserved slot and posts a command; the thread that
// owns the tick applies the commands at the next tick boundary without allocating.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <vector>

#include "tacta/ecs.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/scene.hpp"
#include "world/device_components.hpp"
#include "world/entity_commands.hpp"
#include "world/shape_components.hpp"
#include "world/soft_body.hpp"

namespace tacta {

class World {
 public:
  World(const SceneDesc& scene, const PluginRegistry& plugins);
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const SceneDesc& scene() const noexcept { return scene_; }
  // Slots in use: the scene's bodies, then the added ones in the order they were requested
  // (pending, present or removed; a slot is never reused, so indices stay valid for the run).
  size_t body_count() const noexcept { return body_count_.load(std::memory_order_acquire); }
  size_t body_capacity() const noexcept { return body_entities_.size(); }
  size_t device_count() const noexcept { return devices_.size(); }
  // Slot i's components (entity index = body slot). A removed body's stay for the report.
  SoftBody body(size_t i) const noexcept;
  // Two of slot i's components alone, for the haptic tick's per-surface checks (body() looks up
  // a dozen pools: about 440 instructions).
  bool body_present(size_t i) const noexcept {
    return registry_.pool<BodyPresence>().at(static_cast<uint32_t>(i)).present();
  }
  NodeState& body_nodes(size_t i) const noexcept {
    return registry_.pool<NodeState>().at(static_cast<uint32_t>(i));
  }
  const BodyDesc& body_desc(size_t i) const { return descs_[i]; }
  // Device i's components. Their pools are made at load and never change, so other threads
  // (device input) reach a device without racing the tick's thread.
  DeviceComponents device(size_t i) const noexcept;
  int body_index(const std::string& name) const;
  // The tool device i carries (its own entity; DeviceLink::tool names it).
  Tool& tool(size_t d) const noexcept {
    return registry_.pool<Tool>().at(device(d).link.tool.index);
  }
  int device_index(const std::string& name) const;  // -1 when none
  ecs::Registry& registry() noexcept { return registry_; }
  // Bodies in the running scene, with the components Ts (entity index = body slot).
  template <class... Ts>
  ecs::View<InScene, Ts...> bodies_in_scene() noexcept {
    return registry_.view<InScene, Ts...>();
  }
  uint32_t threads() const noexcept { return jobs_->threads(); }
  JobPool& jobs() noexcept { return *jobs_; }  // the scene's `threads`: models' and bodies'

  // Builds a model instance for a body (load time, or a swap requested from a UI thread).
  std::unique_ptr<ModelInstance> make_model(const std::string& model, const ParamSet& params,
                                            const BodyTopology& topology, double dt,
                                            const SourceLocation& where) const;

  // Requests (any thread but the one running the tick; serialised among themselves). add_body
  // builds the body here (mesh, model instance: allocates, throws InputError) and returns its
  // handle; it enters the scene at the next tick boundary. remove_body takes it out at the next
  // boundary; the handle is stale from the request on. `prepare` (may be empty) runs with the
  // body in its slot before the command is posted (what else the body needs: its collision
  // surface); when it throws, the add is undone.
  ecs::Entity add_body(const BodyDesc& desc, const std::function<void(size_t slot)>& prepare = {});
  void remove_body(ecs::Entity handle);
  // Replaces device `d`'s tool at the next tick boundary (any thread but the tick's; builds
  // the shape here: allocates, throws InputError). One change per device waits at a time.
  void change_tool(size_t d, const ShapeDesc& tool);
  // Handles: entity index = body slot; the generation changes when the body is removed.
  ecs::Entity body_handle(size_t body) const;
  bool is_live(ecs::Entity handle) const noexcept;
  // The slot of a live handle; throws InputError naming the body and why the handle is stale.
  size_t body_slot(ecs::Entity handle) const;

  // The tick's side: applies the posted commands (and the scene's timed events due by `time`).
  // No allocation, no lock, no throw.
  void apply_entity_commands(double time) noexcept;

 private:
  // A removed body's generation moves on and carries kRemovedBit, so no handle matches it
  // again, not even the one body_handle() gives for it afterwards.
  static constexpr uint32_t kRemovedBit = 0x80000000u;
  static uint32_t retired_generation(uint32_t live) noexcept {
    const uint32_t next = (live + 1) & ~kRemovedBit;
    return (next == 0 ? 1 : next) | kRemovedBit;
  }
  void enter(size_t slot, double time) noexcept;
  void leave(size_t slot, double time) noexcept;
  BodyParts build_body(const BodyDesc& desc) const;
  // Moves a built body into slot's components (no allocation: the pools hold every slot).
  void install(size_t slot, BodyParts&& parts) noexcept;
  void reserve_body_components(size_t slots);
  void emplace_body_components(ecs::Entity e);

  SceneDesc scene_;
  const PluginRegistry& plugins_;
  std::unique_ptr<JobPool> jobs_;  // plugins' parallel_for workers (scene key `threads`)
  // Every body slot's entity has all body components from load on (reserved, so taking a body
  // in or out only adds or removes its InScene tag). The pools are made at load and never
  // reallocate, so a requester may fill a pending slot while the tick's thread runs views.
  mutable ecs::Registry registry_;
  std::vector<BodyDesc> descs_;                           // per used slot (reserved to capacity)
  std::vector<ecs::Entity> body_entities_;                // per slot, created at load
  std::unique_ptr<std::atomic<uint32_t>[]> generations_;  // per slot: the live handle's generation
  std::atomic<size_t> body_count_{0};
  std::vector<ecs::Entity> devices_;
  std::vector<ecs::Entity> colliders_;  // the scene's obstacles, in order
  // Per device: a tool waiting for the tick boundary. The tick swaps it with the device's Tool,
  // so the outgoing tool stays here and is freed by the next request, not on the tick's thread.
  struct PendingTool {
    std::atomic<bool> waiting{false};
    Tool tool;
  };
  std::unique_ptr<PendingTool[]> pending_tools_;
  std::vector<Tool> timed_tools_;  // the scene's change_tool events, built at load
  void swap_tool(size_t d, Tool& incoming) noexcept;
  std::mutex requests_;  // serialises requesters only; the tick's thread never takes it
  EntityCommandRing commands_;
  std::vector<EntityCommand> timed_;  // the scene's events, by time
  size_t next_timed_ = 0;
};

}  // namespace tacta
