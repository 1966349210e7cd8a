// A device's evolving state as bytes, for the checkpoint entries (device_api.h save_state /
// load_state): plain fields in a fixed order, the size checked on load.
#pragma once

#include <cstddef>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace tacta::devices {

// Writes the fields into bytes when capacity is enough; returns their size either way.
template <class... Fields>
size_t save_fields(void* bytes, size_t capacity, const Fields&... fields) noexcept {
  static_assert((std::is_trivially_copyable_v<Fields> && ...));
  const size_t size = (sizeof(Fields) + ... + 0);
  if (bytes == nullptr || capacity < size) return size;
  auto* out = static_cast<unsigned char*>(bytes);
  ((std::memcpy(out, &fields, sizeof(Fields)), out += sizeof(Fields)), ...);
  return size;
}

// Reads the fields back; throws std::invalid_argument when the size is not theirs.
template <class... Fields>
void load_fields(const char* device, const void* bytes, size_t size, Fields&... fields) {
  static_assert((std::is_trivially_copyable_v<Fields> && ...));
  const size_t expected = (sizeof(Fields) + ... + 0);
  if (size != expected)
    throw std::invalid_argument(std::string(device) + ": state of " + std::to_string(size) +
                                " bytes, expected " + std::to_string(expected));
  const auto* in = static_cast<const unsigned char*>(bytes);
  ((std::memcpy(&fields, in, sizeof(Fields)), in += sizeof(Fields)), ...);
}

}  // namespace tacta::devices
