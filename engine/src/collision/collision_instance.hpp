// RAII owner of one collision plugin instance (created from its descriptor and scene
// parameters), with the entries the engine resolved from its function table.
#pragma once

#include <cstddef>
#include <string>

#include "tacta/collision_api.h"
#include "tacta/plugin_registry.hpp"

namespace tacta {

constexpr size_t kCollisionMessageCapacity = 1024;  // bytes a plugin may write a reason into

class CollisionInstance {
 public:
  CollisionInstance(const LoadedDescriptor& found, const ParamSet& params, double dt,
                    const SourceLocation& where)
      : descriptor(*found.descriptor),
        api(*static_cast<const tacta_collision_api*>(found.descriptor->api)),
        params_(params),
        dt_(dt) {
    int guessed = 0;
    roles = tacta_collision_roles(&descriptor, &guessed);
    roles_guessed = guessed != 0;
    // Appended after roles: absent from a table built against an older header.
    if (descriptor.api_size >= offsetof(tacta_collision_api, update_elements) + sizeof(void*) &&
        api.element_order != nullptr && api.update_elements != nullptr) {
      element_order = api.element_order;
      update_elements = api.update_elements;
    }
    if (descriptor.api_size >= offsetof(tacta_collision_api, proxy_flags) + sizeof(uint32_t))
      proxy_flags = api.proxy_flags;
    instance = create_sibling(where);
  }
  // A fresh instance of the same plugin with the same parameters and tick (a surface built off
  // the tick and swapped in: SurfaceReplacement); the caller destroys it with api.destroy.
  // Allocates; throws InputError when the plugin refuses.
  void* create_sibling(const SourceLocation& where) const {
    tacta_collision_setup setup{sizeof(tacta_collision_setup), params_.data(), params_.size(), dt_};
    char message[kCollisionMessageCapacity] = {0};
    void* made = nullptr;
    if (api.create(&setup, &made, message, sizeof message) != TACTA_OK || made == nullptr)
      throw InputError(where, std::string("collision plugin '") + descriptor.name +
                                  "' could not be created: " + message);
    return made;
  }
  ~CollisionInstance() {
    if (instance != nullptr) api.destroy(instance);
  }
  CollisionInstance(const CollisionInstance&) = delete;
  CollisionInstance& operator=(const CollisionInstance&) = delete;
  const tacta_descriptor& descriptor;
  const tacta_collision_api& api;
  void* instance = nullptr;
  uint32_t roles = 0;          // TACTA_COLLISION_ROLE_* it serves
  bool roles_guessed = false;  // from its entries: built against a header without `roles`
  // Both or neither (a refit spread over ticks).
  decltype(tacta_collision_api::element_order) element_order = nullptr;
  decltype(tacta_collision_api::update_elements) update_elements = nullptr;
  uint32_t proxy_flags = 0;  // TACTA_COLLISION_PROXY_* (0 from a table that predates them)

 private:
  ParamSet params_;  // as create() saw them, for siblings
  double dt_ = 0;    // s
};

}  // namespace tacta
