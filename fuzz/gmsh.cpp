// Fuzzes load_volume with gmsh input (the format is read from the content, so every volume reader
// is reachable; the seeds start it in gmsh).
#include "load_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tacta::fuzz::load_volume_input(".msh", data, size);
  return 0;
}
