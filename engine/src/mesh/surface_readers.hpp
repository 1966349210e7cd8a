// The surface files read before (or instead of) assimp. PLY and OBJ are read here: assimp 5.2
// crashes on a PLY face index out of range, aborts on a face with no index, loops forever on a
// PLY header it half recognises, drops an OBJ vertex whose number does not parse (later faces then
// land on the wrong vertices) and zero-fills 16 MB per OBJ. STL is checked, then read by assimp.
// Every reader checks the whole file, has no loop the file's bytes can keep going, and throws
// InputError with the file and the line (or, in binary data, the element and item).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

namespace tacta::mesh_detail {

struct PolygonSoup {
  std::vector<double> positions;      // 3 per vertex, as the file holds them
  std::vector<uint32_t> indices;      // every face's vertex indices, one face after the other
  std::vector<uint32_t> face_starts;  // face f is indices[face_starts[f], face_starts[f + 1])
  std::vector<double> corner_uvs;     // u v per entry of indices when the file has them, else empty
  std::vector<std::string> warnings;  // what was ignored (an attribute that did not parse, ...)
};

// An attribute a simulation does not use (texture coordinates, normals, colours) that did not
// parse: the file still loads, without it, and one warning names the first place and the count.
struct IgnoredAttribute {
  explicit IgnoredAttribute(const char* attribute) : what(attribute) {}
  const char* what;  // "texture coordinates", ...
  size_t count = 0;
  int first_line = 0;  // 0 in binary data
  std::string first_problem;
  void note(int line, const std::string& problem) {
    if (count++ == 0) first_line = line, first_problem = problem;
  }
};

// One warning for all of a file's ignored attributes (none when nothing was ignored).
inline void warn_ignored(const std::string& path,
                         std::initializer_list<const IgnoredAttribute*> attributes,
                         std::vector<std::string>& warnings) {
  std::string text;
  for (const IgnoredAttribute* a : attributes) {
    if (a->count == 0) continue;
    text += std::string(text.empty() ? "" : "; ") + a->what + " (" + std::to_string(a->count) +
            (a->count == 1 ? " problem" : " problems") + ", the first at " + path +
            (a->first_line > 0 ? ":" + std::to_string(a->first_line) : std::string()) + ": " +
            a->first_problem + ")";
  }
  if (!text.empty()) warnings.push_back("ignored, as a simulation does not use them: " + text);
}

// True when the file is to be read as PLY: its first bytes are "ply" or its extension is .ply.
bool is_ply(const std::string& path, const std::string& bytes);

// PLY (ascii, binary_little_endian, binary_big_endian; facts from Greg Turk's 1994 description):
// the header's grammar, counts against the file size, value types, every face at least 3
// indices, all below the vertex count.
PolygonSoup read_ply(const std::string& path, const std::string& bytes);

// OBJ: v lines (x y z, optional w or r g b) of finite numbers, vt and vn checked likewise, f lines
// of at least 3 vertices (v, v/vt, v//vn, v/vt/vn; negative = relative) that exist.
PolygonSoup read_obj(const std::string& path, const std::string& bytes);

// OFF (ASCII; OFF, COFF, NOFF, CNOFF, STOFF ...): one vertex a line (x y z, then colour, normal
// or texture values that are ignored), one face a line (n i1 .. in, then an ignored colour);
// '#' starts a comment. 4OFF, nOFF and binary OFF are refused.
PolygonSoup read_off(const std::string& path, const std::string& bytes);

// VTK PolyData, legacy (.vtk, DATASET POLYDATA, ASCII or BINARY) and XML (.vtp: ascii, inline
// binary, appended raw or base64, zlib-compressed): the points, the polygons (fans later) and the
// triangle strips (split into triangles); vertex and line cells are ignored with one warning.
PolygonSoup read_vtk_legacy_polydata(const std::string& path, const std::string& bytes);
PolygonSoup read_vtk_xml_polydata(const std::string& path, const std::string& bytes);

// Appends VTK polygon or strip cells (offsets from 0, one more than the cells) whose indices
// refer to the points from first_point on; strips become triangles with the strip's winding.
// Errors name the file and `line`.
void add_vtk_polygons(const std::string& path, int line, const std::vector<int64_t>& offsets,
                      const std::vector<int64_t>& connectivity, bool strips, size_t first_point,
                      PolygonSoup& out);
void warn_ignored_cells(size_t vertices, size_t lines, PolygonSoup& out);

// A binary STL is exactly 84 + 50 bytes per facet; otherwise the file is ASCII STL: solid, facets
// of three finite vertices each, endsolid, nothing else.
void check_stl(const std::string& path, const std::string& bytes);

// glTF 2.0 (.gltf, or the JSON chunk of a .glb), before assimp: every mesh primitive has a mode in
// [0, 6], a POSITION accessor that exists and enough vertices for its mode. Not a full validator.
void check_gltf(const std::string& path, const std::string& bytes);

}  // namespace tacta::mesh_detail
