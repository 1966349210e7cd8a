// Fuzzes load_surface with a .ply file (assimp picks its importer from the extension and content).
#include "load_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tacta::fuzz::load_surface_input(".ply", data, size);
  return 0;
}
