// The data of VTK XML files (.vtu, .vtp): the document with its raw appended data set aside (it
// is not XML), and DataArrays in any of the encodings VTK writes. Facts from "VTK File Formats"
// (Kitware), XML section, and vtkXMLDataParser/vtkZLibDataCompressor (header layouts).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <tinyxml2.h>
#include <vector>

#include "tacta/error.hpp"

namespace tacta::mesh_detail {

struct XmlContext {
  std::string path;
  bool big_endian = false;
  int header_bytes = 4;  // UInt32 or UInt64 byte counts before binary data
  bool zlib = false;
  std::string_view appended;     // the bytes after '_' in <AppendedData>, empty when none
  bool appended_base64 = false;  // encoding="base64"; else "raw"
  [[noreturn]] void fail(const tinyxml2::XMLElement* where, const std::string& message) const {
    throw InputError({path, where ? where->GetLineNum() : 0, 0, ""}, message);
  }
};

// Parses text (which must outlive ctx.appended) into doc and returns the <VTKFile> root with ctx
// filled from its attributes; refuses a root whose type is not `type`, saying what `type` holds.
const tinyxml2::XMLElement* parse_vtk_xml(const std::string& path, const std::string& text,
                                          const char* type, const char* what_type_holds,
                                          tinyxml2::XMLDocument& doc, XmlContext& ctx);

// Values of one DataArray (ascii, binary or appended; any VTK scalar type) as doubles, exactly
// `count` of them, all finite (integer types: whole numbers). Every VTK integer a mesh needs is
// exact in a double.
std::vector<double> read_array(const XmlContext& ctx, const tinyxml2::XMLElement* array,
                               size_t count);

// The cells of a <Cells>, <Polys>, <Strips> ... element: its "offsets" (count ends, checked not
// to decrease) and "connectivity" arrays. offsets gets a leading 0; an index out of any range
// becomes -1 (check_vtk_cell reports it); line is the connectivity array's.
struct XmlCells {
  std::vector<int64_t> offsets, connectivity;
  int line = 0;
};
XmlCells read_cells(const XmlContext& ctx, const tinyxml2::XMLElement* parent, size_t count);

const tinyxml2::XMLElement* child(const XmlContext& ctx, const tinyxml2::XMLElement* parent,
                                  const char* name);
// A count attribute in [0, 2e9]; a missing one is an error unless `optional` (then 0).
int64_t count_attribute(const XmlContext& ctx, const tinyxml2::XMLElement* e, const char* name,
                        bool optional = false);

}  // namespace tacta::mesh_detail
