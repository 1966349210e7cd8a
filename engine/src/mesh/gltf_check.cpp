#include <cstdint>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>

#include "mesh/surface_readers.hpp"
#include "tacta/error.hpp"

namespace tacta::mesh_detail {

namespace {

// Vertices a primitive needs for its mode (glTF 2.0 mesh.primitive.mode, 0..6).
int64_t least_vertices(int64_t mode) {
  if (mode == 0) return 1;  // points
  if (mode <= 3) return 2;  // lines, line loop, line strip
  return 3;                 // triangles, strip, fan
}

// A member of an object, or null when j is not an object or lacks it (const operator[] would be
// undefined behaviour on a missing key).
const nlohmann::json& member(const nlohmann::json& j, const char* key) {
  static const nlohmann::json kNull;
  if (!j.is_object()) return kNull;
  auto it = j.find(key);
  return it == j.end() ? kNull : *it;
}

int64_t accessor_count(const nlohmann::json& accessors, const nlohmann::json& index) {
  if (!index.is_number_unsigned() || index.get<uint64_t>() >= accessors.size()) return -1;
  const nlohmann::json& count = member(accessors[index.get<size_t>()], "count");
  return count.is_number_integer() ? count.get<int64_t>() : -1;
}

}  // namespace

void check_gltf(const std::string& path, const std::string& bytes) {
  std::string text = bytes;
  if (bytes.size() >= 20 && std::memcmp(bytes.data(), "glTF", 4) == 0) {
    uint32_t json_length = 0;  // the first chunk of a .glb is the JSON, its length at byte 12
    std::memcpy(&json_length, bytes.data() + 12, sizeof json_length);
    if (json_length > bytes.size() - 20)
      throw InputError({path, 0, 0, ""}, "the .glb JSON chunk runs past the file's end");
    text = bytes.substr(20, json_length);
  }
  const nlohmann::json gltf = nlohmann::json::parse(text, nullptr, false);
  if (gltf.is_discarded() || !gltf.is_object())
    throw InputError({path, 0, 0, ""}, "the glTF JSON does not parse");
  const nlohmann::json& meshes = member(gltf, "meshes");
  const nlohmann::json& accessors = member(gltf, "accessors");
  if (meshes.is_null()) return;
  if (!meshes.is_array() || !accessors.is_array()) {
    throw InputError({path, 0, 0, ""}, "glTF meshes and accessors must be arrays");
  }
  for (size_t m = 0; m < meshes.size(); ++m) {
    const nlohmann::json& primitives = member(meshes[m], "primitives");
    if (!primitives.is_array())
      throw InputError({path, 0, 0, ""},
                       "glTF mesh " + std::to_string(m) + " has no primitives array");
    for (size_t p = 0; p < primitives.size(); ++p) {
      const std::string where =
          "glTF mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      const nlohmann::json& given_mode = member(primitives[p], "mode");
      const int64_t mode = given_mode.is_null()              ? 4
                           : given_mode.is_number_unsigned() ? given_mode.get<int64_t>()
                                                             : -1;
      if (mode < 0 || mode > 6)
        throw InputError({path, 0, 0, ""}, where + ": mode must be an integer in [0, 6]");
      // assimp 5.2 asks for (vertices - 1) faces of a strip without positions: a 64 GB allocation.
      const nlohmann::json& position = member(member(primitives[p], "attributes"), "POSITION");
      if (position.is_null())
        throw InputError({path, 0, 0, ""}, where + " has no POSITION attribute");
      const nlohmann::json& indices = member(primitives[p], "indices");
      const int64_t positions = accessor_count(accessors, position);
      const int64_t used = indices.is_null() ? positions : accessor_count(accessors, indices);
      if (positions < 1 || used < least_vertices(mode)) {
        throw InputError(
            {path, 0, 0, ""},
            where + ": its POSITION or indices accessor is missing or holds fewer than " +
                std::to_string(least_vertices(mode)) + " items for mode " + std::to_string(mode));
      }
    }
  }
}

}  // namespace tacta::mesh_detail
