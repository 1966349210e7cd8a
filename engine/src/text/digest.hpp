// FNV-1a 64 over bytes and its 16-hex-digit text: the run's state hash (hash_positions) and the
// checkpoint's checksum and scene fingerprint share it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace tacta {

// FNV-1a 64 over `size` bytes at `data`, continuing from `h` (the offset basis to start).
inline uint64_t fnv1a64(const void* data, size_t size,
                        uint64_t h = 1469598103934665603ull) noexcept {
  const auto* p = static_cast<const unsigned char*>(data);
  for (size_t i = 0; i < size; ++i) {
    h ^= p[i];
    h *= 1099511628211ull;  // FNV-1a 64 prime
  }
  return h;
}

// "00ab..." : 16 lower-case hex digits.
inline std::string hex64(uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

}  // namespace tacta
