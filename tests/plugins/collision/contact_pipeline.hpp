// Test helper: the engine's per-tick collision pipeline over the real plugin libraries
// (bvh: refit + pairs; ccd: exact contacts on the pairs; convex: vertices against tools and
// obstacles; ccd: respond), as engine/src/collision/collision_context.cpp runs it.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "plugin_fixture.hpp"
#include "tacta/collision_api.h"

namespace tacta::testing {

class CollisionPlugin {
 public:
  CollisionPlugin(const std::string& file, const std::string& name,
                  const std::vector<std::pair<std::string, double>>& overrides = {})
      : plugin_(file), api_(plugin_.api<tacta_collision_api>(name)) {
    const tacta_descriptor& d = plugin_.descriptor(name);
    auto params = default_params(d);
    for (const auto& [key, value] : overrides) {
      bool found = false;
      for (uint32_t i = 0; i < d.param_count; ++i)
        if (key == d.params[i].name) params[i].number = value, found = true;
      if (!found) throw std::runtime_error(name + ": no parameter " + key);
    }
    tacta_collision_setup setup{sizeof setup, params.data(), static_cast<uint32_t>(params.size()),
                                1e-3};
    char message[256] = {0};
    if (api_.create(&setup, &instance_, message, sizeof message) != TACTA_OK)
      throw std::runtime_error(name + ": create failed: " + message);
  }
  ~CollisionPlugin() { api_.destroy(instance_); }
  CollisionPlugin(const CollisionPlugin&) = delete;
  CollisionPlugin& operator=(const CollisionPlugin&) = delete;
  const tacta_collision_api& api() const { return api_; }
  void* instance() const { return instance_; }

 private:
  LoadedPlugin plugin_;
  const tacta_collision_api& api_;
  void* instance_ = nullptr;
};

struct TickResult {
  uint32_t bits = 0;
  uint32_t surface_contacts = 0;  // vertex-face and edge-edge
  uint32_t shape_contacts = 0;    // vertices against tools and obstacles
  int rounds = 0;                 // detect + respond rounds run
};

class ContactPipeline {
 public:
  explicit ContactPipeline(double friction)
      : ccd_("tacta_ccd.so", "ccd", {{"friction", friction}}) {}

  // Call once the world's arrays are in place (and again if their sizes change).
  void prepare(const tacta_collision_world& world) {
    char message[256] = {0};
    if (bvh_.api().prepare(bvh_.instance(), &world, message, sizeof message) != TACTA_OK)
      throw std::runtime_error(std::string("bvh prepare: ") + message);
  }

  // Up to three rounds of detect + respond, the next round only while surface-surface contacts
  // appear (the response's corrections are motions that the next round's CCD checks).
  TickResult tick(tacta_collision_world& world) {
    TickResult r;
    contact_count_ = 0;
    for (int round = 0; round < 3; ++round) {
      r.bits |= bvh_.api().update(bvh_.instance(), &world);
      uint32_t pair_count = 0, surface = 0, shape = 0;
      const uint32_t first = contact_count_;
      r.bits |= bvh_.api().find_pairs(bvh_.instance(), &world, pairs_.data(),
                                      static_cast<uint32_t>(pairs_.size()), &pair_count);
      r.bits |= ccd_.api().detect(ccd_.instance(), &world, pairs_.data(), pair_count,
                                  contacts_.data() + first,
                                  static_cast<uint32_t>(contacts_.size()) - first, &surface);
      r.bits |= convex_.api().detect(
          convex_.instance(), &world, nullptr, 0, contacts_.data() + first + surface,
          static_cast<uint32_t>(contacts_.size()) - first - surface, &shape);
      contact_count_ = first + surface + shape;
      r.surface_contacts += surface;
      r.shape_contacts += shape;
      r.bits |=
          ccd_.api().respond(ccd_.instance(), &world, contacts_.data() + first, surface + shape);
      ++r.rounds;
      if (surface == 0) break;
    }
    return r;
  }
  const tacta_contact* contacts() const { return contacts_.data(); }
  uint32_t contact_count() const { return contact_count_; }
  const CollisionPlugin& ccd() const { return ccd_; }
  const CollisionPlugin& convex() const { return convex_; }

 private:
  CollisionPlugin bvh_{"tacta_bvh.so", "bvh", {{"self_collision", 0.0}}};
  CollisionPlugin ccd_;
  CollisionPlugin convex_{"tacta_convex.so", "convex"};
  std::vector<tacta_collision_pair> pairs_ = std::vector<tacta_collision_pair>(200000);
  std::vector<tacta_contact> contacts_ = std::vector<tacta_contact>(100000);
  uint32_t contact_count_ = 0;
};

// A plane obstacle n . x = offset (world), static.
inline tacta_collision_shape plane(double nx, double ny, double nz, double offset) {
  tacta_collision_shape s{};
  s.type = TACTA_SHAPE_PLANE;
  s.plane_normal[0] = nx;
  s.plane_normal[1] = ny;
  s.plane_normal[2] = nz;
  s.plane_offset = offset;
  s.pose_start = s.pose_end = {{0, 0, 0}, {1, 0, 0, 0}};
  return s;
}

inline tacta_collision_shape sphere_tool(double radius, double x, double y, double z) {
  tacta_collision_shape s{};
  s.type = TACTA_SHAPE_SPHERE;
  s.radius = radius;
  s.pose_start = s.pose_end = {{x, y, z}, {1, 0, 0, 0}};
  return s;
}

}  // namespace tacta::testing
