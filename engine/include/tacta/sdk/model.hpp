// SDK adapter: write an elastic model as a class; model_descriptor<T>() fills tacta_model_api.
//
// T needs:
//   static constexpr const char* kName, kDescription;  static constexpr uint32_t kVersion;
//   static constexpr std::array<tacta_param_spec, N> kParams;
//   explicit T(const tacta_model_setup&)            may throw std::invalid_argument on bad input
//   uint32_t step(tacta_body_state&, double dt) noexcept      1 kHz path: no allocation
// and optionally, each filling the matching optional entry only when present:
//   void begin(const tacta_body_state&, double dt) noexcept
//   double elastic_energy(const double* positions) noexcept
//   void internal_forces(const double* positions, double* forces) noexcept
//   void set_param(uint32_t index, const tacta_param_value&)   may throw
//   void node_stress(const double* positions, double* von_mises) noexcept
//   uint32_t counters(tacta_model_counter* out, uint32_t capacity) noexcept
//   std::string describe() const          what the instance chose that its parameters did not say
//   static constexpr uint32_t kClaims      TACTA_MODEL_CLAIM_* bits (checked by tacta check-plugin)
//   static constexpr const char* kLiveParams  "a|b": what set_param changes without a swap
//   size_t save_state(void* bytes, size_t capacity) noexcept    checkpoint: see model_api.h
//   void load_state(const void* bytes, size_t size)    throws std::invalid_argument on a bad blob
#pragma once

#include <cstring>
#include <string>

#include "tacta/model_api.h"
#include "tacta/sdk/common.hpp"

namespace tacta::sdk {

// For a model's counters(): copies what fits into out and returns how many there are.
inline uint32_t copy_counters(const tacta_model_counter* all, uint32_t count,
                              tacta_model_counter* out, uint32_t capacity) noexcept {
  for (uint32_t i = 0; i < count && i < capacity; ++i) out[i] = all[i];
  return count;
}

template <class T>
struct ModelAdapter {
  static tacta_status create(const tacta_model_setup* setup, void** instance, char* message,
                             size_t capacity) noexcept {
    return guarded(message, capacity, [&] { *instance = new T(*setup); });
  }
  static void destroy(void* instance) noexcept { delete static_cast<T*>(instance); }
  static uint32_t step(void* instance, tacta_body_state* state, double dt) noexcept {
    return static_cast<T*>(instance)->step(*state, dt);
  }
  static void begin(void* instance, const tacta_body_state* state, double dt) noexcept {
    static_cast<T*>(instance)->begin(*state, dt);
  }
  static double elastic_energy(void* instance, const double* positions) noexcept {
    return static_cast<T*>(instance)->elastic_energy(positions);
  }
  static void internal_forces(void* instance, const double* positions, double* forces) noexcept {
    static_cast<T*>(instance)->internal_forces(positions, forces);
  }
  static tacta_status set_param(void* instance, uint32_t index, const tacta_param_value* value,
                                char* message, size_t capacity) noexcept {
    return guarded(message, capacity, [&] { static_cast<T*>(instance)->set_param(index, *value); });
  }
  static void node_stress(void* instance, const double* positions, double* von_mises) noexcept {
    static_cast<T*>(instance)->node_stress(positions, von_mises);
  }
  static uint32_t counters(void* instance, tacta_model_counter* out, uint32_t capacity) noexcept {
    return static_cast<T*>(instance)->counters(out, capacity);
  }

  static void describe(void* instance, char* text, size_t capacity) noexcept {
    if (capacity == 0) return;
    text[0] = '\0';
    try {
      const std::string said = static_cast<const T*>(instance)->describe();
      std::strncpy(text, said.c_str(), capacity - 1);
      text[capacity - 1] = '\0';
    } catch (...) {
    }
  }

  static size_t save_state(void* instance, void* bytes, size_t capacity) noexcept {
    return static_cast<T*>(instance)->save_state(bytes, capacity);
  }
  static tacta_status load_state(void* instance, const void* bytes, size_t size, char* message,
                                 size_t capacity) noexcept {
    return guarded(message, capacity, [&] { static_cast<T*>(instance)->load_state(bytes, size); });
  }

  static tacta_model_api table() {
    tacta_model_api api{};
    api.create = &create;
    api.destroy = &destroy;
    api.step = &step;
    if constexpr (requires(T & t, const tacta_body_state& s) { t.begin(s, 0.0); })
      api.begin = &begin;
    if constexpr (requires(T & t, const double* x) { t.elastic_energy(x); })
      api.elastic_energy = &elastic_energy;
    if constexpr (requires(T & t, const double* x, double* f) { t.internal_forces(x, f); })
      api.internal_forces = &internal_forces;
    if constexpr (requires(T & t, const tacta_param_value& v) { t.set_param(0u, v); })
      api.set_param = &set_param;
    if constexpr (requires(T & t, const double* x, double* s) { t.node_stress(x, s); })
      api.node_stress = &node_stress;
    if constexpr (requires(T & t, tacta_model_counter * c) { t.counters(c, 0u); })
      api.counters = &counters;
    if constexpr (requires(const T& t) { t.describe(); }) api.describe = &describe;
    if constexpr (requires { T::kClaims; }) api.claims = T::kClaims;
    if constexpr (requires { T::kLiveParams; }) api.live_params = T::kLiveParams;
    if constexpr (requires(T & t, void* b, const void* c) {
                    t.save_state(b, size_t{0});
                    t.load_state(c, size_t{0});
                  }) {
      api.save_state = &save_state;
      api.load_state = &load_state;
    }
    return api;
  }
};

template <class T>
const tacta_descriptor* model_descriptor() {
  static const tacta_model_api api = ModelAdapter<T>::table();
  return class_descriptor<T>(TACTA_KIND_MODEL, api);
}

}  // namespace tacta::sdk
