// What a cut's collision side is made of before it is swapped in (CollisionContext::
// prepare_replacement / apply_replacement): built off the tick over a copy of the view, so the
// tick that takes it in only exchanges buffers and instance pointers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "collision/proxy_freshness.hpp"
#include "tacta/collision_api.h"

namespace tacta {

class EmbeddedCollisionSurface;

// Resized with room for a quarter more: a cut adds a few vertices at a time, and growing past
// the capacity moves the whole buffer to fresh pages (milliseconds between two ticks).
template <class T>
void resize_with_room(std::vector<T>& v, size_t count) {
  if (count > v.capacity()) v.reserve(count + count / 4);
  v.resize(count);
}

// The collision view's positions as they stood at a tick boundary (CollisionContext::copy_view):
// per surface, the start and end positions the plugins see (for an embedded surface its
// vertices, current only where the last queries looked) and, for an embedded surface, its body's
// node positions at the start and end of the tick (3 per node, m); the tools' shapes; the time.
struct ViewCopy {
  struct Surface {
    std::vector<double> start, end;            // 3 per vertex, m
    std::vector<double> node_start, node_end;  // embedded only: 3 per node, m
  };
  std::vector<Surface> surfaces;
  std::vector<tacta_collision_shape> tools;
  double time = 0, dt = 0;  // s
  bool filled = false;      // copy_view found room for everything
};

// A fresh collision plugin instance, destroyed with its plugin's destroy().
struct PluginInstance {
  PluginInstance(const tacta_collision_api& a, void* made) : api(&a), instance(made) {}
  PluginInstance(PluginInstance&& o) noexcept : api(o.api), instance(o.instance) {
    o.instance = nullptr;
  }
  PluginInstance& operator=(PluginInstance&&) = delete;
  PluginInstance(const PluginInstance&) = delete;
  ~PluginInstance() {
    if (instance != nullptr) api->destroy(instance);
  }
  const tacta_collision_api* api;
  void* instance;
};

// One body's collision surface made for a cut's new shape, with every plugin instance made
// again and built over it; after apply_replacement it holds what it replaced, to be destroyed
// off the tick.
struct SurfaceReplacement {
  SurfaceReplacement();
  SurfaceReplacement(SurfaceReplacement&&) noexcept;
  SurfaceReplacement& operator=(SurfaceReplacement&&) noexcept;
  ~SurfaceReplacement();

  static constexpr size_t kNone = static_cast<size_t>(-1);
  size_t body = 0;
  size_t surface = kNone;                 // kNone: the body does not collide, nothing to swap
  size_t surface_count = 0;               // the view's surfaces it was built with
  tacta_collision_surface description{};  // the live view's, over the arrays the body will have
  std::vector<double> inverse_masses;     // 1 per node, 1/kg
  std::unique_ptr<EmbeddedCollisionSurface> embedded;  // null: the tets' boundary
  std::optional<SurfaceFreshness> freshness;
  std::vector<PluginInstance> instances;  // one per CollisionInstance, same order
  uint32_t build_bits = 0;                // TACTA_COLLIDE_* the builds returned
  // The sizes the context's buffers need for the new shape, and buffers made with room for them
  // where the current ones lack it (else empty).
  size_t pairs_needed = 0, contacts_needed = 0, patch_needed = 0;
  std::vector<tacta_collision_pair> pairs;
  std::vector<tacta_contact> contacts;
  std::vector<uint32_t> patch_triangles;
};

}  // namespace tacta
