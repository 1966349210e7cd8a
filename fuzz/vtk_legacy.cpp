// Fuzzes load_volume with vtk_legacy input (the format is read from the content, so every volume reader
// is reachable; the seeds start it in vtk_legacy).
#include "load_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tacta::fuzz::load_volume_input(".vtk", data, size);
  return 0;
}
