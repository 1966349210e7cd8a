// Fuzzes load_surface with a legacy .vtk file (DATASET POLYDATA, ASCII or BINARY).
#include "load_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tacta::fuzz::load_surface_input(".vtk", data, size);
  return 0;
}
