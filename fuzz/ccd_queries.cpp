// Fuzzes the engine's reader of the CCD query files (tests/data/ccd), the one the CCD tests, the
// benchmark and `tacta ccd-bench` call. Bad text must end in an InputError, nothing else.
#include "tacta/ccd_queries.hpp"

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "tacta/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    (void)tacta::read_ccd_queries(in, "fuzz.csv", true);
  } catch (const tacta::InputError&) {
  }
  return 0;
}
