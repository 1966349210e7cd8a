// The mesh harnesses: the input becomes a file with the format's extension and goes through the
// loader `tacta mesh-info` and scenes use. An InputError is the expected answer to bad bytes;
// anything else (a crash, a sanitizer report, another exception, a hang) is a finding.
#pragma once

#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta::fuzz {

// Writes the input to this process's file with `extension` and loads it with load(path, report).
template <class Load>
void load_input(const char* extension, const uint8_t* data, size_t size, Load load) {
  static const std::string path = input_path(extension);
  try {
    LoadReport report;
    load(write_input(path, data, size), report);
  } catch (const InputError&) {
  }
}

inline void load_volume_input(const char* extension, const uint8_t* data, size_t size) {
  load_input(extension, data, size, [](const std::string& path, LoadReport& report) {
    (void)mesh_quality(load_volume(path, &report));
  });
}

inline void load_surface_input(const char* extension, const uint8_t* data, size_t size) {
  load_input(extension, data, size, [](const std::string& path, LoadReport& report) {
    (void)enclosed_volume(load_surface(path, &report));
  });
}

}  // namespace tacta::fuzz
