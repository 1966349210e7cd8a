// Fuzzes load_volume with vtk_xml input (the format is read from the content, so every volume reader
// is reachable; the seeds start it in vtk_xml).
#include "load_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tacta::fuzz::load_volume_input(".vtu", data, size);
  return 0;
}
