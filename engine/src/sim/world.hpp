// The world of one run: an ECS registry holding a SoftBody per body and a DeviceSlot per device,
// built from a validated scene. Building either completes or throws InputError; nothing is left
// half-loaded.
#pragma once

#include <memory>
#include <vector>

#include "device_slot.hpp"
#include "soft_body.hpp"
#include "tacta/ecs.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/scene.hpp"

namespace tacta {

class World {
 public:
  World(const SceneDesc& scene, const PluginRegistry& plugins);
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  const SceneDesc& scene() const noexcept { return scene_; }
  size_t body_count() const noexcept { return bodies_.size(); }
  size_t device_count() const noexcept { return devices_.size(); }
  // Entities stay valid for the world's life: nothing is created or destroyed after loading.
  SoftBody& body(size_t i) { return registry_.get<SoftBody>(bodies_[i]); }
  const SoftBody& body(size_t i) const { return registry_.get<SoftBody>(bodies_[i]); }
  DeviceSlot& device(size_t i) { return registry_.get<DeviceSlot>(devices_[i]); }
  const DeviceSlot& device(size_t i) const { return registry_.get<DeviceSlot>(devices_[i]); }
  int body_index(const std::string& name) const;
  ecs::Registry& registry() noexcept { return registry_; }
  uint32_t threads() const noexcept { return jobs_->threads(); }

  // Builds a model instance for a body (load time, or a swap requested from a UI thread).
  std::unique_ptr<ModelInstance> make_model(const std::string& model, const ParamSet& params,
                                            const BodyTopology& topology, double dt,
                                            const SourceLocation& where) const;

 private:
  SceneDesc scene_;
  const PluginRegistry& plugins_;
  std::unique_ptr<JobPool> jobs_;  // plugins' parallel_for workers (scene key `threads`)
  ecs::Registry registry_;
  std::vector<ecs::Entity> bodies_;
  std::vector<ecs::Entity> devices_;
};

}  // namespace tacta
