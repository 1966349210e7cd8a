// Fuzzes load_surface with a .vtp file (VTK XML PolyData: ascii, binary, appended, zlib).
#include "load_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tacta::fuzz::load_surface_input(".vtp", data, size);
  return 0;
}
