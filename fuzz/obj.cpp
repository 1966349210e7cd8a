// Fuzzes load_surface with a .obj file (assimp picks its importer from the extension and content).
#include "load_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  tacta::fuzz::load_surface_input(".obj", data, size);
  return 0;
}
