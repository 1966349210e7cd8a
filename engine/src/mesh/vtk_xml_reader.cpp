// VTK XML UnstructuredGrid (.vtu) through tinyxml2: DataArrays in ascii, or inline binary (base64
// of a byte-count header, UInt32 or UInt64, then the data), optionally zlib-compressed in blocks.
// Appended data is not supported. Facts from "VTK File Formats" (Kitware), XML section.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <tinyxml2.h>
#include <vector>
#include <zlib.h>

#include "mesh/readers.hpp"
#include "mesh/text_reader.hpp"
#include "mesh/vtk_cells.hpp"

namespace tacta::mesh_detail {

namespace {

using tinyxml2::XMLElement;

constexpr double kMaxIndex = 4e9;  // beyond any uint32 index a mesh can hold

struct XmlContext {
  std::string path;
  bool big_endian = false;
  int header_bytes = 4;  // UInt32 or UInt64 byte counts before binary data
  bool zlib = false;
  [[noreturn]] void fail(const XMLElement* where, const std::string& message) const {
    throw InputError({path, where ? where->GetLineNum() : 0, 0, ""}, message);
  }
};

int base64_value(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+') return 62;
  if (c == '/') return 63;
  return -1;
}

// Decodes base64 group by group, so that separately padded streams (header, then data) written
// one after the other decode to their concatenation.
std::vector<unsigned char> decode_base64(const XmlContext& ctx, const XMLElement* where,
                                         const char* text) {
  std::string clean;
  for (const char* p = text; *p; ++p) {
    if (!std::isspace(static_cast<unsigned char>(*p))) clean += *p;
  }
  if (clean.size() % 4 != 0)
    ctx.fail(where, "base64 data length is not a multiple of 4 (truncated?)");
  std::vector<unsigned char> bytes;
  bytes.reserve(clean.size() / 4 * 3);
  for (size_t g = 0; g < clean.size(); g += 4) {
    int v[4];
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      char c = clean[g + static_cast<size_t>(k)];
      if (c == '=' && k >= 2) {
        v[k] = 0;
        ++pad;
      } else {
        v[k] = base64_value(c);
        if (v[k] < 0 || pad > 0) ctx.fail(where, "invalid base64 character in binary data");
      }
    }
    uint32_t triple = (static_cast<uint32_t>(v[0]) << 18) | (static_cast<uint32_t>(v[1]) << 12) |
                      (static_cast<uint32_t>(v[2]) << 6) | static_cast<uint32_t>(v[3]);
    bytes.push_back(static_cast<unsigned char>(triple >> 16));
    if (pad < 2) bytes.push_back(static_cast<unsigned char>(triple >> 8));
    if (pad < 1) bytes.push_back(static_cast<unsigned char>(triple));
  }
  return bytes;
}

uint64_t read_unsigned(const unsigned char* p, int size, bool big_endian) {
  uint64_t value = 0;
  for (int i = 0; i < size; ++i) {
    int byte = big_endian ? i : size - 1 - i;
    value = (value << 8) | p[byte];
  }
  return value;
}

struct ScalarType {
  int size = 0;
  bool is_float = false, is_signed = false;
};

ScalarType scalar_type(const XmlContext& ctx, const XMLElement* array) {
  const char* name = array->Attribute("type");
  std::string t = name ? name : "";
  if (t == "Float32") return {4, true, true};
  if (t == "Float64") return {8, true, true};
  if (t == "Int8" || t == "Char") return {1, false, true};
  if (t == "UInt8") return {1, false, false};
  if (t == "Int16") return {2, false, true};
  if (t == "UInt16") return {2, false, false};
  if (t == "Int32") return {4, false, true};
  if (t == "UInt32") return {4, false, false};
  if (t == "Int64") return {8, false, true};
  if (t == "UInt64") return {8, false, false};
  ctx.fail(array, "DataArray type '" + t + "' is not a VTK scalar type");
}

double to_double(const unsigned char* p, ScalarType type, bool big_endian) {
  uint64_t raw = read_unsigned(p, type.size, big_endian);
  if (type.is_float) {
    if (type.size == 4) {
      uint32_t bits = static_cast<uint32_t>(raw);
      float f;
      std::memcpy(&f, &bits, 4);
      return static_cast<double>(f);
    }
    double d;
    std::memcpy(&d, &raw, 8);
    return d;
  }
  if (type.is_signed && type.size < 8 && (raw >> (8 * type.size - 1)) != 0) {
    raw |= ~uint64_t{0} << (8 * type.size);  // sign-extend
  }
  return type.is_signed ? static_cast<double>(static_cast<int64_t>(raw)) : static_cast<double>(raw);
}

std::vector<unsigned char> binary_payload(const XmlContext& ctx, const XMLElement* array,
                                          size_t expected_bytes) {
  const char* text = array->GetText();
  std::vector<unsigned char> bytes = decode_base64(ctx, array, text ? text : "");
  const size_t h = static_cast<size_t>(ctx.header_bytes);
  auto header_word = [&](size_t index) {
    if ((index + 1) * h > bytes.size())
      ctx.fail(array, "binary data ends inside its header (truncated?)");
    return read_unsigned(bytes.data() + index * h, ctx.header_bytes, ctx.big_endian);
  };
  if (!ctx.zlib) {
    uint64_t size = header_word(0);
    if (size != expected_bytes) {
      ctx.fail(array, "binary header says " + std::to_string(size) + " bytes, the array needs " +
                          std::to_string(expected_bytes));
    }
    if (h + size > bytes.size())
      ctx.fail(array, "binary data is shorter than its header says (truncated?)");
    return {bytes.begin() + static_cast<std::ptrdiff_t>(h),
            bytes.begin() + static_cast<std::ptrdiff_t>(h + size)};
  }
  uint64_t blocks = header_word(0), block_size = header_word(1), last_size = header_word(2);
  if (blocks > bytes.size()) ctx.fail(array, "compressed header gives an impossible block count");
  uint64_t total =
      blocks == 0 ? 0 : (blocks - 1) * block_size + (last_size == 0 ? block_size : last_size);
  if (total != expected_bytes) {
    ctx.fail(array, "compressed header says " + std::to_string(total) + " bytes, the array needs " +
                        std::to_string(expected_bytes));
  }
  std::vector<unsigned char> out(expected_bytes);
  size_t src = (3 + blocks) * h, dst = 0;
  for (uint64_t b = 0; b < blocks; ++b) {
    uint64_t compressed = header_word(3 + b);
    if (src + compressed > bytes.size())
      ctx.fail(array, "compressed block " + std::to_string(b) + " is cut short (truncated?)");
    uLongf produced =
        static_cast<uLongf>(b + 1 == blocks && last_size != 0 ? last_size : block_size);
    if (dst + produced > out.size() || uncompress(out.data() + dst, &produced, bytes.data() + src,
                                                  static_cast<uLong>(compressed)) != Z_OK) {
      ctx.fail(array,
               "compressed block " + std::to_string(b) + " does not inflate (corrupt zlib data)");
    }
    src += compressed;
    dst += produced;
  }
  if (dst != expected_bytes)
    ctx.fail(array, "compressed blocks inflate to fewer bytes than the header says");
  return out;
}

// Values of one DataArray as doubles (every VTK integer a mesh needs is exact in a double).
std::vector<double> read_array(const XmlContext& ctx, const XMLElement* array, size_t count) {
  ScalarType type = scalar_type(ctx, array);
  const char* format_attr = array->Attribute("format");
  std::string format = format_attr ? format_attr : "ascii";
  std::vector<double> values;
  if (format == "ascii") {
    const char* text = array->GetText();
    TextReader in(ctx.path, text ? text : "");
    while (!in.at_end()) {
      values.push_back(in.next_double("a DataArray value"));
      if (values.size() > count) break;
    }
  } else if (format == "binary") {
    std::vector<unsigned char> bytes =
        binary_payload(ctx, array, count * static_cast<size_t>(type.size));
    values.resize(count);
    for (size_t i = 0; i < count; ++i)
      values[i] =
          to_double(bytes.data() + i * static_cast<size_t>(type.size), type, ctx.big_endian);
  } else {
    ctx.fail(array,
             "DataArray format '" + format + "' is not supported (ascii and inline binary are)");
  }
  if (values.size() != count) {
    const char* name = array->Attribute("Name");
    ctx.fail(array, std::string("DataArray ") + (name ? name : "") + " must hold " +
                        std::to_string(count) + " values, it holds " +
                        (values.size() > count ? "more" : std::to_string(values.size())));
  }
  for (double v : values) {
    if (!std::isfinite(v)) ctx.fail(array, "DataArray holds a NaN or infinite value");
    if (!type.is_float && v != std::floor(v)) ctx.fail(array, "integer DataArray holds a fraction");
  }
  return values;
}

const XMLElement* named_array(const XmlContext& ctx, const XMLElement* parent, const char* name) {
  for (const XMLElement* a = parent->FirstChildElement("DataArray"); a;
       a = a->NextSiblingElement("DataArray")) {
    const char* n = a->Attribute("Name");
    if (n && std::strcmp(n, name) == 0) return a;
  }
  ctx.fail(parent, std::string("<Cells> has no DataArray named '") + name + "'");
}

const XMLElement* child(const XmlContext& ctx, const XMLElement* parent, const char* name) {
  const XMLElement* c = parent->FirstChildElement(name);
  if (!c) ctx.fail(parent, std::string("<") + parent->Name() + "> has no <" + name + "> element");
  return c;
}

int64_t count_attribute(const XmlContext& ctx, const XMLElement* e, const char* name) {
  int64_t value = -1;
  if (e->QueryInt64Attribute(name, &value) != tinyxml2::XML_SUCCESS || value < 0 ||
      value > 2'000'000'000) {
    ctx.fail(e, std::string("<") + e->Name() + "> needs a non-negative integer attribute " + name);
  }
  return value;
}

void read_piece(const XmlContext& ctx, const XMLElement* piece, VolumeMesh& out,
                LoadReport& report) {
  size_t points = static_cast<size_t>(count_attribute(ctx, piece, "NumberOfPoints"));
  size_t cells = static_cast<size_t>(count_attribute(ctx, piece, "NumberOfCells"));
  size_t first_point = out.positions.size() / 3;
  const XMLElement* point_array = child(ctx, child(ctx, piece, "Points"), "DataArray");
  int components = point_array->IntAttribute("NumberOfComponents", 1);
  if (components != 3) ctx.fail(point_array, "point coordinates need NumberOfComponents=\"3\"");
  std::vector<double> xyz = read_array(ctx, point_array, 3 * points);
  out.positions.insert(out.positions.end(), xyz.begin(), xyz.end());

  const XMLElement* cell_node = child(ctx, piece, "Cells");
  const XMLElement* offsets_array = named_array(ctx, cell_node, "offsets");
  std::vector<double> offsets = read_array(ctx, offsets_array, cells);
  std::vector<double> types = read_array(ctx, named_array(ctx, cell_node, "types"), cells);
  double previous = 0;
  for (double o : offsets) {
    if (o < previous) ctx.fail(offsets_array, "cell offsets must not decrease");
    if (o > kMaxIndex)
      ctx.fail(offsets_array, "cell offset " + std::to_string(o) + " is too large");
    previous = o;
  }
  const XMLElement* connectivity_array = named_array(ctx, cell_node, "connectivity");
  std::vector<double> connectivity =
      read_array(ctx, connectivity_array, static_cast<size_t>(previous));
  std::vector<int64_t> indices;
  size_t begin = 0;
  for (size_t c = 0; c < cells; ++c) {
    size_t end = static_cast<size_t>(offsets[c]);
    indices.clear();
    for (size_t k = begin; k < end; ++k) {
      // Out-of-range values become -1 before the cast, and check_vtk_cell reports them.
      double v = connectivity[k];
      indices.push_back(v >= 0 && v <= kMaxIndex ? static_cast<int64_t>(v) : -1);
    }
    begin = end;
    int64_t type = types[c] >= 0 && types[c] <= 255 ? static_cast<int64_t>(types[c]) : -1;
    check_vtk_cell(ctx.path, connectivity_array->GetLineNum(), c, type, indices, points);
    if (type != kVtkTetra) {
      ++report.skipped_elements;
      continue;
    }
    for (int64_t i : indices)
      out.tets.push_back(static_cast<uint32_t>(first_point + static_cast<size_t>(i)));
  }
}

}  // namespace

VolumeMesh read_vtk_xml(const std::string& path, const std::string& text, LoadReport& report) {
  report.format = "vtk-xml";
  XmlContext ctx{path};
  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.data(), text.size()) != tinyxml2::XML_SUCCESS) {
    const char* message = doc.ErrorStr();
    throw InputError({path, doc.ErrorLineNum(), 0, ""},
                     std::string("malformed XML (truncated?): ") + (message ? message : ""));
  }
  const XMLElement* root = doc.FirstChildElement("VTKFile");
  if (!root) ctx.fail(nullptr, "no <VTKFile> element");
  const char* type = root->Attribute("type");
  if (!type || std::strcmp(type, "UnstructuredGrid") != 0) {
    ctx.fail(root, std::string("VTKFile type '") + (type ? type : "") +
                       "' holds no tetrahedra; UnstructuredGrid does");
  }
  const char* order = root->Attribute("byte_order");
  ctx.big_endian = order && std::strcmp(order, "BigEndian") == 0;
  const char* header = root->Attribute("header_type");
  if (header && std::strcmp(header, "UInt64") == 0) {
    ctx.header_bytes = 8;
  } else if (header && std::strcmp(header, "UInt32") != 0) {
    ctx.fail(root, std::string("header_type '") + header + "' is not UInt32 or UInt64");
  }
  const char* compressor = root->Attribute("compressor");
  if (compressor && std::strcmp(compressor, "vtkZLibDataCompressor") == 0) {
    ctx.zlib = true;
  } else if (compressor && *compressor) {
    ctx.fail(root, std::string("compressor '") + compressor +
                       "' is not supported (vtkZLibDataCompressor is)");
  }
  const XMLElement* grid = child(ctx, root, "UnstructuredGrid");
  VolumeMesh out;
  out.source = path;
  int pieces = 0;
  for (const XMLElement* piece = grid->FirstChildElement("Piece"); piece;
       piece = piece->NextSiblingElement("Piece")) {
    read_piece(ctx, piece, out, report);
    ++pieces;
  }
  if (pieces == 0) ctx.fail(grid, "<UnstructuredGrid> has no <Piece>");
  return out;
}

}  // namespace tacta::mesh_detail
