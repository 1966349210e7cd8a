// SDK adapter: write a haptic device as a class; device_descriptor<T>() fills tacta_device_api.
//
// T needs:
//   static constexpr const char* kName, kDescription;  static constexpr uint32_t kVersion;
//   static constexpr std::array<tacta_param_spec, N> kParams;
//   explicit T(const tacta_device_setup&)                    may throw std::invalid_argument
//   void connect()                                          may throw (message goes to the host)
//   void disconnect() noexcept
//   tacta_device_state read(double time, tacta_device_sample&) noexcept     1 kHz path
//   void write(double time, const tacta_device_command&) noexcept          1 kHz path
//   tacta_device_capabilities capabilities() const noexcept
// optionally:
//   tacta_device_state status(char* reason, size_t capacity) const noexcept
//   static void input(T* instance_or_null, const double* values, uint32_t count) noexcept
//       host-fed input (lock-free); a null instance means every live instance
//   void surface(const tacta_device_surface&) noexcept     render thread; copy what you keep
//   uint32_t counters(tacta_device_counter*, uint32_t capacity) const noexcept   for report.json
//   size_t save_state(void* bytes, size_t capacity) const noexcept     checkpoints (device_api.h)
//   void load_state(const void* bytes, size_t size)   may throw std::invalid_argument (the reason)
#pragma once

#include "tacta/device_api.h"
#include "tacta/sdk/common.hpp"

namespace tacta::sdk {

template <class T>
struct DeviceAdapter {
  static tacta_status create(const tacta_device_setup* setup, void** instance, char* message,
                             size_t capacity) noexcept {
    return guarded(message, capacity, [&] { *instance = new T(*setup); });
  }
  static void destroy(void* instance) noexcept { delete static_cast<T*>(instance); }
  static tacta_status connect(void* instance, char* message, size_t capacity) noexcept {
    return guarded(message, capacity, [&] { static_cast<T*>(instance)->connect(); });
  }
  static void disconnect(void* instance) noexcept { static_cast<T*>(instance)->disconnect(); }
  static tacta_device_state read(void* instance, double time,
                                 tacta_device_sample* sample) noexcept {
    return static_cast<T*>(instance)->read(time, *sample);
  }
  static void write(void* instance, double time, const tacta_device_command* command) noexcept {
    static_cast<T*>(instance)->write(time, *command);
  }
  static void capabilities(void* instance, tacta_device_capabilities* out) noexcept {
    *out = static_cast<T*>(instance)->capabilities();
  }
  static tacta_device_state status(void* instance, char* reason, size_t capacity) noexcept {
    return static_cast<T*>(instance)->status(reason, capacity);
  }
  static void input(void* instance, const double* values, uint32_t count) noexcept {
    T::input(static_cast<T*>(instance), values, count);
  }

  static void surface(void* instance, const tacta_device_surface* s) noexcept {
    static_cast<T*>(instance)->surface(*s);
  }
  static uint32_t counters(void* instance, tacta_device_counter* out, uint32_t capacity) noexcept {
    return static_cast<const T*>(instance)->counters(out, capacity);
  }
  static size_t save_state(void* instance, void* bytes, size_t capacity) noexcept {
    return static_cast<const T*>(instance)->save_state(bytes, capacity);
  }
  static tacta_status load_state(void* instance, const void* bytes, size_t size, char* message,
                                 size_t capacity) noexcept {
    return guarded(message, capacity, [&] { static_cast<T*>(instance)->load_state(bytes, size); });
  }

  static tacta_device_api table() {
    tacta_device_api api{};
    api.create = &create;
    api.destroy = &destroy;
    api.connect = &connect;
    api.disconnect = &disconnect;
    api.read = &read;
    api.write = &write;
    api.capabilities = &capabilities;
    if constexpr (requires(const T& t, char* r) { t.status(r, size_t{0}); }) api.status = &status;
    if constexpr (requires(T * t, const double* v) { T::input(t, v, uint32_t{0}); })
      api.input = &input;
    if constexpr (requires(T & t, const tacta_device_surface& s) { t.surface(s); })
      api.surface = &surface;
    if constexpr (requires(const T& t, tacta_device_counter* c) { t.counters(c, uint32_t{0}); })
      api.counters = &counters;
    if constexpr (requires(const T& t, T& m, void* b, const void* c) {
                    t.save_state(b, size_t{0});
                    m.load_state(c, size_t{0});
                  }) {
      api.save_state = &save_state;
      api.load_state = &load_state;
    }
    return api;
  }
};

template <class T>
const tacta_descriptor* device_descriptor() {
  static const tacta_device_api api = DeviceAdapter<T>::table();
  return class_descriptor<T>(TACTA_KIND_DEVICE, api);
}

}  // namespace tacta::sdk
