// The surface files read before (or instead of) assimp. PLY and OBJ are read here: assimp 5.2
// crashes on a PLY face index out of range, aborts on a face with no index, loops forever on a
// PLY header it half recognises, drops an OBJ vertex whose number does not parse (later faces then
// land on the wrong vertices) and zero-fills 16 MB per OBJ. STL is checked, then read by assimp.
// Every reader checks the whole file, has no loop the file's bytes can keep going, and throws
// InputError with the file and the line (or, in binary data, the element and item).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tacta::mesh_detail {

struct PolygonSoup {
  std::vector<double> positions;      // 3 per vertex, as the file holds them
  std::vector<uint32_t> indices;      // every face's vertex indices, one face after the other
  std::vector<uint32_t> face_starts;  // face f is indices[face_starts[f], face_starts[f + 1])
  std::vector<double> corner_uvs;     // u v per entry of indices when the file has them, else empty
};

// True when the file is to be read as PLY: its first bytes are "ply" or its extension is .ply.
bool is_ply(const std::string& path, const std::string& bytes);

// PLY (ascii, binary_little_endian, binary_big_endian; facts from Greg Turk's 1994 description):
// the header's grammar, counts against the file size, value types, every face at least 3
// indices, all below the vertex count.
PolygonSoup read_ply(const std::string& path, const std::string& bytes);

// OBJ: v lines (x y z, optional w or r g b) of finite numbers, vt and vn checked likewise, f lines
// of at least 3 vertices (v, v/vt, v//vn, v/vt/vn; negative = relative) that exist.
PolygonSoup read_obj(const std::string& path, const std::string& bytes);

// A binary STL is exactly 84 + 50 bytes per facet; otherwise the file is ASCII STL: solid, facets
// of three finite vertices each, endsolid, nothing else.
void check_stl(const std::string& path, const std::string& bytes);

// glTF 2.0 (.gltf, or the JSON chunk of a .glb), before assimp: every mesh primitive has a mode in
// [0, 6], a POSITION accessor that exists and enough vertices for its mode. Not a full validator.
void check_gltf(const std::string& path, const std::string& bytes);

}  // namespace tacta::mesh_detail
