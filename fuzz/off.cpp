// Fuzzes load_surface with a .off file (Tacta's own OFF reader).
#include "load_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tacta::fuzz::load_surface_input(".off", data, size);
  return 0;
}
