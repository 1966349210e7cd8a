// Fuzzes the reader of the CCD query files (tests/data/ccd) that the CCD tests and benchmarks use.
#include "ccd_queries.hpp"

#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = tacta::fuzz::input_path(".csv");
  try {
    (void)tacta::testing::read_ccd_queries(tacta::fuzz::write_input(path, data, size));
  } catch (const std::runtime_error&) {
  }
  return 0;
}
