// SDK adapter: write a collision method as a class; collision_descriptor<T>() fills
// tacta_collision_api, setting each optional entry only when T has the matching member.
//
// T needs:
//   static constexpr const char* kName, kDescription;  static constexpr uint32_t kVersion;
//   static constexpr std::array<tacta_param_spec, N> kParams;
//   explicit T(const tacta_collision_setup&)          may throw std::invalid_argument
// and any of (per-tick members are noexcept and allocate nothing):
//   void prepare(const tacta_collision_world&)        may throw std::invalid_argument
//   uint32_t update(const tacta_collision_world&) noexcept
//   uint32_t find_pairs(const tacta_collision_world&, tacta_collision_pair*, uint32_t capacity,
//                       uint32_t& count) noexcept
//   uint32_t overlap_shape(const tacta_collision_world&, const tacta_collision_shape&,
//                          uint32_t surface, uint32_t* triangles, uint32_t capacity,
//                          uint32_t& count) noexcept
//   bool sphere_cast(const tacta_collision_world&, uint32_t surface, const double* from,
//                    const double* to, double radius, tacta_surface_hit&) noexcept
//   bool closest_point(const tacta_collision_world&, uint32_t surface, const double* point,
//                      double max_distance, tacta_surface_hit&) noexcept
//   uint32_t detect(const tacta_collision_world&, const tacta_collision_pair* pairs,
//                   uint32_t pair_count, tacta_contact*, uint32_t capacity,
//                   uint32_t& count) noexcept
//   bool vertex_face(const double* points, tacta_ccd_hit&) noexcept
//   bool edge_edge(const double* points, tacta_ccd_hit&) noexcept
//   uint32_t shape_query(const tacta_collision_shape& a, const tacta_collision_shape* b,
//                        const double* triangle, tacta_shape_result&) noexcept
//   uint32_t respond(tacta_collision_world&, tacta_contact*, uint32_t count) noexcept
//   uint32_t element_order(uint32_t surface, const uint32_t*& order, uint32_t& count) noexcept
//   uint32_t update_elements(const tacta_collision_world&, uint32_t surface, uint32_t first,
//                            uint32_t count) noexcept
//   static constexpr uint32_t kProxyFlags          TACTA_COLLISION_PROXY_* bits
#pragma once

#include "tacta/collision_api.h"
#include "tacta/sdk/common.hpp"

namespace tacta::sdk {

template <class T>
struct CollisionAdapter {
  static T& self(void* instance) noexcept { return *static_cast<T*>(instance); }

  static tacta_status create(const tacta_collision_setup* setup, void** instance, char* message,
                             size_t capacity) noexcept {
    return guarded(message, capacity, [&] { *instance = new T(*setup); });
  }
  static void destroy(void* instance) noexcept { delete static_cast<T*>(instance); }
  static tacta_status prepare(void* instance, const tacta_collision_world* world, char* message,
                              size_t capacity) noexcept {
    return guarded(message, capacity, [&] { self(instance).prepare(*world); });
  }
  static uint32_t update(void* instance, const tacta_collision_world* world) noexcept {
    return self(instance).update(*world);
  }
  static uint32_t find_pairs(void* instance, const tacta_collision_world* world,
                             tacta_collision_pair* pairs, uint32_t capacity,
                             uint32_t* count) noexcept {
    return self(instance).find_pairs(*world, pairs, capacity, *count);
  }
  static uint32_t overlap_shape(void* instance, const tacta_collision_world* world,
                                const tacta_collision_shape* shape, uint32_t surface,
                                uint32_t* triangles, uint32_t capacity, uint32_t* count) noexcept {
    return self(instance).overlap_shape(*world, *shape, surface, triangles, capacity, *count);
  }
  static int32_t sphere_cast(void* instance, const tacta_collision_world* world, uint32_t surface,
                             const double from[3], const double to[3], double radius,
                             tacta_surface_hit* hit) noexcept {
    return self(instance).sphere_cast(*world, surface, from, to, radius, *hit) ? 1 : 0;
  }
  static int32_t closest_point(void* instance, const tacta_collision_world* world, uint32_t surface,
                               const double point[3], double max_distance,
                               tacta_surface_hit* hit) noexcept {
    return self(instance).closest_point(*world, surface, point, max_distance, *hit) ? 1 : 0;
  }
  static uint32_t detect(void* instance, const tacta_collision_world* world,
                         const tacta_collision_pair* pairs, uint32_t pair_count,
                         tacta_contact* contacts, uint32_t capacity, uint32_t* count) noexcept {
    return self(instance).detect(*world, pairs, pair_count, contacts, capacity, *count);
  }
  static int32_t vertex_face(void* instance, const double points[24], tacta_ccd_hit* hit) noexcept {
    return self(instance).vertex_face(points, *hit) ? 1 : 0;
  }
  static int32_t edge_edge(void* instance, const double points[24], tacta_ccd_hit* hit) noexcept {
    return self(instance).edge_edge(points, *hit) ? 1 : 0;
  }
  static uint32_t shape_query(void* instance, const tacta_collision_shape* a,
                              const tacta_collision_shape* b, const double* triangle,
                              tacta_shape_result* result) noexcept {
    return self(instance).shape_query(*a, b, triangle, *result);
  }
  static uint32_t respond(void* instance, tacta_collision_world* world, tacta_contact* contacts,
                          uint32_t contact_count) noexcept {
    return self(instance).respond(*world, contacts, contact_count);
  }

  static uint32_t element_order(void* instance, uint32_t surface, const uint32_t** order,
                                uint32_t* count) noexcept {
    return self(instance).element_order(surface, *order, *count);
  }
  static uint32_t update_elements(void* instance, const tacta_collision_world* world,
                                  uint32_t surface, uint32_t first, uint32_t count) noexcept {
    return self(instance).update_elements(*world, surface, first, count);
  }

  static tacta_collision_api table() {
    using World = const tacta_collision_world&;
    tacta_collision_api api{};
    api.create = &create;
    api.destroy = &destroy;
    if constexpr (requires(T & t, World w) { t.prepare(w); }) api.prepare = &prepare;
    if constexpr (requires(T & t, World w) { t.update(w); }) api.update = &update;
    if constexpr (requires(T & t, World w, tacta_collision_pair * p, uint32_t & n) {
                    t.find_pairs(w, p, 0u, n);
                  })
      api.find_pairs = &find_pairs;
    if constexpr (requires(T & t, World w, const tacta_collision_shape& s, uint32_t* o,
                           uint32_t& n) { t.overlap_shape(w, s, 0u, o, 0u, n); })
      api.overlap_shape = &overlap_shape;
    if constexpr (requires(T & t, World w, const double* x, tacta_surface_hit& h) {
                    t.sphere_cast(w, 0u, x, x, 0.0, h);
                  })
      api.sphere_cast = &sphere_cast;
    if constexpr (requires(T & t, World w, const double* x, tacta_surface_hit& h) {
                    t.closest_point(w, 0u, x, 0.0, h);
                  })
      api.closest_point = &closest_point;
    if constexpr (requires(T & t, World w, const tacta_collision_pair* p, tacta_contact* c,
                           uint32_t& n) { t.detect(w, p, 0u, c, 0u, n); })
      api.detect = &detect;
    if constexpr (requires(T & t, const double* x, tacta_ccd_hit& h) { t.vertex_face(x, h); })
      api.vertex_face = &vertex_face;
    if constexpr (requires(T & t, const double* x, tacta_ccd_hit& h) { t.edge_edge(x, h); })
      api.edge_edge = &edge_edge;
    if constexpr (requires(T & t, const tacta_collision_shape& s, const double* x,
                           tacta_shape_result& r) { t.shape_query(s, &s, x, r); })
      api.shape_query = &shape_query;
    if constexpr (requires(T & t, tacta_collision_world & w, tacta_contact * c) {
                    t.respond(w, c, 0u);
                  })
      api.respond = &respond;
    if constexpr (requires { T::kRoles; }) api.roles = T::kRoles;  // TACTA_COLLISION_ROLE_* bits
    if constexpr (requires(T & t, World w, const uint32_t*& o, uint32_t& n) {
                    t.element_order(0u, o, n);
                    t.update_elements(w, 0u, 0u, 0u);
                  }) {
      api.element_order = &element_order;
      api.update_elements = &update_elements;
    }
    if constexpr (requires { T::kProxyFlags; }) api.proxy_flags = T::kProxyFlags;
    return api;
  }
};

template <class T>
const tacta_descriptor* collision_descriptor() {
  static const tacta_collision_api api = CollisionAdapter<T>::table();
  return class_descriptor<T>(TACTA_KIND_COLLISION, api);
}

}  // namespace tacta::sdk
