// Fuzzes the device log reader (tacta/device_log.hpp) that the replay device plays from.
#include "tacta/device_log.hpp"

#include <cstddef>
#include <cstdint>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    (void)tacta::parse_device_log(std::string_view(reinterpret_cast<const char*>(data), size),
                                  "fuzz.csv");
  } catch (const tacta::InputError&) {
  }
  return 0;
}
