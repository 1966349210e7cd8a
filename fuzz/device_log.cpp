// Fuzzes the device log reader (tacta/device_log.hpp) that the replay device plays from.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "tacta/device_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    (void)tacta::parse_device_log(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.csv");
  } catch (const tacta::InputError&) {
  }
  return 0;
}
