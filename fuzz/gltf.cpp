// Fuzzes load_surface with glTF: binary .glb when the input starts with the "glTF" magic, JSON
// .gltf otherwise (buffers then come as data: URIs; a file URI is looked up next to the input).
#include <cstring>

#include "load_mesh.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  tacta::fuzz::load_surface_input(binary ? ".glb" : ".gltf", data, size);
  return 0;
}
