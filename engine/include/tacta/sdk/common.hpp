// Header-only C++ SDK for writing Tacta plugins as classes. This part: parameter access, message
// buffers and the exported entry point. The kind-specific adapters (model.hpp, device.hpp,
// collision.hpp) fill the C function tables from a class, so no C++ type crosses the boundary.
#pragma once

#include <cstring>
#include <exception>
#include <initializer_list>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "tacta/plugin.h"

namespace tacta::sdk {

// Copies text into a C message buffer, truncated and always NUL-terminated.
inline void write_message(char* buffer, size_t capacity, std::string_view text) noexcept {
  if (buffer == nullptr || capacity == 0) return;
  const size_t n = text.size() < capacity - 1 ? text.size() : capacity - 1;
  std::memcpy(buffer, text.data(), n);
  buffer[n] = '\0';
}

// Runs fn (which may throw) and turns an exception into a status plus message.
template <class Fn>
tacta_status guarded(char* message, size_t capacity, Fn&& fn) noexcept {
  try {
    fn();
    return TACTA_OK;
  } catch (const std::bad_alloc&) {
    write_message(message, capacity, "out of memory");
    return TACTA_ERR_OUT_OF_MEMORY;
  } catch (const std::invalid_argument& e) {
    write_message(message, capacity, e.what());
    return TACTA_ERR_INVALID_ARGUMENT;
  } catch (const std::exception& e) {
    write_message(message, capacity, e.what());
    return TACTA_ERR_INTERNAL;
  } catch (...) {
    write_message(message, capacity, "unknown exception in plugin");
    return TACTA_ERR_INTERNAL;
  }
}

// Read access to validated parameter values by name. The engine has already checked types and
// ranges against the schema, so lookups by a name the schema declares cannot fail at run time;
// an unknown name is a programming error in the plugin and throws std::invalid_argument.
class Params {
 public:
  Params(std::span<const tacta_param_spec> schema, const tacta_param_value* values, uint32_t count)
      : schema_(schema), values_(values), count_(count) {}

  double real(std::string_view name) const { return value(name).number; }
  int integer(std::string_view name) const { return static_cast<int>(value(name).number); }
  bool flag(std::string_view name) const { return value(name).number != 0.0; }
  int choice(std::string_view name) const { return static_cast<int>(value(name).number); }
  std::string_view choice_name(std::string_view name) const { return text(name); }
  std::string_view text(std::string_view name) const {
    const char* t = value(name).text;
    return t ? std::string_view(t) : std::string_view();
  }
  std::span<const double> vector(std::string_view name) const {
    const tacta_param_value& v = value(name);
    return v.values ? std::span<const double>(v.values, v.count) : std::span<const double>();
  }

 private:
  const tacta_param_value& value(std::string_view name) const {
    for (size_t i = 0; i < schema_.size() && i < count_; ++i)
      if (name == schema_[i].name) return values_[i];
    throw std::invalid_argument("parameter '" + std::string(name) + "' is not in the schema");
  }
  std::span<const tacta_param_spec> schema_;
  const tacta_param_value* values_;
  uint32_t count_;
};

// Parameter spec builders, so a plugin's schema reads as a table.
constexpr tacta_param_spec real_param(const char* name, const char* unit, double def, double lo,
                                      double hi, const char* help) {
  return {name, TACTA_PARAM_REAL, unit, def, lo, hi, nullptr, nullptr, 0, help};
}
constexpr tacta_param_spec int_param(const char* name, double def, double lo, double hi,
                                     const char* help) {
  return {name, TACTA_PARAM_INT, "", def, lo, hi, nullptr, nullptr, 0, help};
}
constexpr tacta_param_spec bool_param(const char* name, bool def, const char* help) {
  return {name, TACTA_PARAM_BOOL, "", def ? 1.0 : 0.0, 0.0, 1.0, nullptr, nullptr, 0, help};
}
constexpr tacta_param_spec choice_param(const char* name, const char* choices, int def,
                                        const char* help) {
  return {name, TACTA_PARAM_CHOICE, "", static_cast<double>(def), 0.0, 0.0, choices, nullptr, 0,
          help};
}
constexpr tacta_param_spec text_param(const char* name, const char* def, const char* help) {
  return {name, TACTA_PARAM_TEXT, "", 0.0, 0.0, 0.0, nullptr, def, 0, help};
}
constexpr tacta_param_spec vector_param(const char* name, const char* unit, unsigned stride,
                                        const char* def, double lo, double hi, const char* help) {
  return {name, TACTA_PARAM_VECTOR, unit, 0.0, lo, hi, nullptr, def, stride, help};
}

// The descriptor of plugin class T (its kName, kVersion, kDescription, kParams) of `kind`, over
// its function table `api`, which must have static storage. One per (T, Api): lives as long as
// the library, as the host requires.
template <class T, class Api>
const tacta_descriptor* class_descriptor(tacta_kind kind, const Api& api) {
  static const tacta_descriptor descriptor{sizeof(tacta_descriptor),
                                           TACTA_ABI_ID,
                                           kind,
                                           T::kName,
                                           T::kVersion,
                                           T::kDescription,
                                           T::kParams.data(),
                                           static_cast<uint32_t>(T::kParams.size()),
                                           &api,
                                           sizeof(Api)};
  return &descriptor;
}

// Registers descriptors with the host after checking the ABI; the body of tacta_plugin_entry.
inline tacta_status register_descriptors(uint64_t host_abi, const tacta_host* host, char* message,
                                         size_t capacity,
                                         std::initializer_list<const tacta_descriptor*> list) {
  if (!tacta_abi_check(host_abi, TACTA_ABI_ID, message, capacity)) return TACTA_ERR_ABI;
  if (host == nullptr || host->register_descriptor == nullptr) {
    write_message(message, capacity, "host table has no register_descriptor");
    return TACTA_ERR_INVALID_ARGUMENT;
  }
  for (const tacta_descriptor* d : list) {
    const tacta_status s = host->register_descriptor(host->context, d);
    if (s != TACTA_OK) {
      write_message(message, capacity, std::string("host refused descriptor '") + d->name + "'");
      return s;
    }
  }
  return TACTA_OK;
}

}  // namespace tacta::sdk

// Defines the exported entry point; pass descriptor pointers, e.g.
//   TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<MyModel>())
#define TACTA_PLUGIN_EXPORT(...)                                                           \
  extern "C" TACTA_EXPORT tacta_status tacta_plugin_entry(                                 \
      uint64_t host_abi, const tacta_host* host, char* message, size_t message_capacity) { \
    return ::tacta::sdk::register_descriptors(host_abi, host, message, message_capacity,   \
                                              {__VA_ARGS__});                              \
  }
