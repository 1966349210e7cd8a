#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string_view>

#include "mesh/surface_readers.hpp"
#include "mesh/text_reader.hpp"
#include "tacta/error.hpp"

namespace tacta::mesh_detail {

namespace {

constexpr int64_t kMaxItems =
    1'000'000'000;                      // items of one element; the file size bounds them first
constexpr int64_t kMaxFaceSize = 1024;  // vertex indices of one face (fan-triangulated)
constexpr int64_t kMaxListLength = 1'000'000;  // items of a list in any other element

enum class Type { None, Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

Type type_named(std::string_view name) {
  if (name == "char" || name == "int8") return Type::Int8;
  if (name == "uchar" || name == "uint8") return Type::UInt8;
  if (name == "short" || name == "int16") return Type::Int16;
  if (name == "ushort" || name == "uint16") return Type::UInt16;
  if (name == "int" || name == "int32") return Type::Int32;
  if (name == "uint" || name == "uint32") return Type::UInt32;
  if (name == "float" || name == "float32") return Type::Float32;
  if (name == "double" || name == "float64") return Type::Float64;
  return Type::None;
}

size_t size_of(Type t) {
  switch (t) {
    case Type::Int8:
    case Type::UInt8: return 1;
    case Type::Int16:
    case Type::UInt16: return 2;
    case Type::Int32:
    case Type::UInt32:
    case Type::Float32: return 4;
    case Type::Float64: return 8;
    case Type::None: break;
  }
  return 0;
}

bool is_integer(Type t) { return t != Type::None && t != Type::Float32 && t != Type::Float64; }

// The range of an integer type, for ASCII values.
std::pair<int64_t, int64_t> range_of(Type t) {
  switch (t) {
    case Type::Int8: return {-128, 127};
    case Type::UInt8: return {0, 255};
    case Type::Int16: return {-32768, 32767};
    case Type::UInt16: return {0, 65535};
    case Type::Int32: return {-2147483648LL, 2147483647LL};
    default: return {0, 4294967295LL};
  }
}

struct Property {
  std::string name;
  Type type = Type::None;        // of the value, or of each list item
  Type count_type = Type::None;  // of a list's length; None for a single value
  bool is_list() const { return count_type != Type::None; }
};

struct Element {
  std::string name;
  int64_t count = 0;
  std::vector<Property> properties;
  int line = 0;
};

struct Header {
  std::string format;
  std::vector<Element> elements;
  size_t data_start = 0;  // byte after the end_header line
  int lines = 0;          // header lines, end_header included
};

std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> words;
  size_t pos = 0;
  while ((pos = line.find_first_not_of(" \t", pos)) != std::string_view::npos) {
    size_t end = std::min(line.find_first_of(" \t", pos), line.size());
    words.push_back(line.substr(pos, end - pos));
    pos = end;
  }
  return words;
}

// Every header line must be one of the grammar's; each pass of the loop consumes a line.
Header parse_header(const std::string& path, const std::string& bytes) {
  auto fail = [&](int line, const std::string& message) {
    throw InputError({path, line, 0, ""}, message);
  };
  Header h;
  size_t pos = 0;
  for (int number = 1;; ++number) {
    const size_t end = bytes.find('\n', pos);
    if (end == std::string::npos)
      fail(number, "the PLY header has no end_header line (truncated?)");
    std::string_view line(bytes.data() + pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    const std::vector<std::string_view> words = words_of(line);
    const std::string_view keyword = words.empty() ? std::string_view() : words[0];
    if (number == 1) {
      if (line != "ply") fail(1, "expected 'ply' alone on the first line of a PLY file");
    } else if (keyword == "comment" || keyword == "obj_info") {
      continue;
    } else if (keyword == "format") {
      if (!h.format.empty() || !h.elements.empty())
        fail(number, "'format' must come once, before the elements");
      if (words.size() != 3 || words[2] != "1.0" ||
          (words[1] != "ascii" && words[1] != "binary_little_endian" &&
           words[1] != "binary_big_endian")) {
        fail(number, "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      }
      h.format = words[1];
    } else if (keyword == "element") {
      Element e;
      if (h.format.empty()) fail(number, "expected the 'format' line before the first element");
      if (words.size() != 3 || !parse_int(words[2], e.count) || e.count < 0 ||
          e.count > kMaxItems) {
        fail(number,
             "expected 'element NAME COUNT' with COUNT in [0, " + std::to_string(kMaxItems) + "]");
      }
      e.name = words[1];
      e.line = number;
      h.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (h.elements.empty()) fail(number, "a PLY property before any element");
      Property p;
      if (words.size() == 5 && words[1] == "list") {
        p = {std::string(words[4]), type_named(words[3]), type_named(words[2])};
        if (!is_integer(p.count_type) || p.type == Type::None) {
          fail(number,
               "expected 'property list COUNT_TYPE ITEM_TYPE NAME' with an integer COUNT_TYPE");
        }
      } else if (words.size() == 3) {
        p = {std::string(words[2]), type_named(words[1]), Type::None};
        if (p.type == Type::None) {
          fail(number,
               "unknown PLY property type '" + std::string(words[1].substr(0, 40)) +
                   "' (char, uchar, short, ushort, int, uint, float, double or int8 ... float64)");
        }
      } else {
        fail(number, "expected 'property TYPE NAME' or 'property list COUNT_TYPE ITEM_TYPE NAME'");
      }
      h.elements.back().properties.push_back(std::move(p));
    } else if (keyword == "end_header") {
      if (words.size() != 1) fail(number, "expected 'end_header' alone on its line");
      if (h.format.empty()) fail(number, "the PLY header has no 'format' line");
      h.data_start = pos;
      h.lines = number;
      return h;
    } else {
      fail(number,
           "expected a PLY header line (format, element, property, comment, obj_info, end_header), "
           "found '" +
               std::string(line.substr(0, 40)) + "'");
    }
  }
}

// Which element and properties hold the surface.
struct Layout {
  size_t vertex = 0, face = 0;  // element indices
  size_t xyz[3] = {0, 0, 0};    // property indices of x, y, z in the vertex element
  size_t face_list = 0;         // property index of vertex_indices in the face element
};

Layout find_layout(const std::string& path, const Header& h) {
  auto find = [&](const std::string& name) {
    for (size_t e = 0; e < h.elements.size(); ++e)
      if (h.elements[e].name == name) return e;
    throw InputError({path, 0, 0, ""}, "the PLY header declares no '" + name + "' element");
  };
  Layout layout;
  layout.vertex = find("vertex");
  layout.face = find("face");
  const Element& vertex = h.elements[layout.vertex];
  const Element& face = h.elements[layout.face];
  if (layout.face < layout.vertex) {
    throw InputError({path, face.line, 0, ""},
                     "the face element must come after the vertex element");
  }
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    auto it = std::find_if(vertex.properties.begin(), vertex.properties.end(),
                           [&](const Property& p) { return p.name == axes[k] && !p.is_list(); });
    if (it == vertex.properties.end()) {
      throw InputError({path, vertex.line, 0, ""},
                       std::string("the vertex element has no property ") + axes[k]);
    }
    layout.xyz[k] = static_cast<size_t>(it - vertex.properties.begin());
  }
  auto list = std::find_if(face.properties.begin(), face.properties.end(), [](const Property& p) {
    return p.is_list() && (p.name == "vertex_indices" || p.name == "vertex_index");
  });
  if (list == face.properties.end() || !is_integer(list->type)) {
    throw InputError({path, face.line, 0, ""},
                     "the face element has no integer list property vertex_indices");
  }
  layout.face_list = static_cast<size_t>(list - face.properties.begin());
  return layout;
}

// Refuses counts the file cannot hold before anything is allocated for them.
void check_counts_fit(const std::string& path, const Header& h, size_t data_bytes) {
  const bool ascii = h.format == "ascii";
  for (const Element& e : h.elements) {
    size_t least = 0;  // bytes of the smallest possible item: one character per ASCII value
    for (const Property& p : e.properties)
      least += ascii ? 1 : size_of(p.is_list() ? p.count_type : p.type);
    if (e.count > 0 && least == 0) {
      throw InputError({path, e.line, 0, ""},
                       "element '" + e.name + "' has items but no properties");
    }
    if (least > 0 && static_cast<uint64_t>(e.count) > data_bytes / least) {
      throw InputError({path, e.line, 0, ""},
                       "element '" + e.name + "' declares " + std::to_string(e.count) +
                           " items, more than the file's data can hold (truncated?)");
    }
    if (least > 0) data_bytes -= static_cast<size_t>(e.count) * least;
  }
}

// ASCII values: tokens with their line numbers.
class AsciiValues {
 public:
  AsciiValues(const std::string& path, const std::string& bytes, int header_lines)
      : in_(path, bytes) {
    for (int i = 0; i < header_lines; ++i) in_.skip_line();
  }
  void at(const std::string&, int64_t) {}
  double value(Type t, const char* what) {
    if (!is_integer(t)) return in_.next_double(what);
    auto [lo, hi] = range_of(t);
    return static_cast<double>(in_.next_int_in(what, lo, hi));
  }
  // A value no simulation needs: one that does not parse or fit its type is noted, not fatal.
  double attribute(Type t, const std::string& name, IgnoredAttribute& ignored) {
    const std::string_view token = in_.next("a PLY value");
    double v = 0;
    bool ok = parse_double(token, v) && std::isfinite(v);
    if (ok && is_integer(t)) {
      auto [lo, hi] = range_of(t);
      ok = v == std::floor(v) && v >= static_cast<double>(lo) && v <= static_cast<double>(hi);
    }
    if (!ok)
      ignored.note(in_.line(), "property '" + name + "': '" + std::string(token.substr(0, 40)) +
                                   "' is not a value of its type");
    return 0;
  }
  [[noreturn]] void fail(const std::string& message) const { in_.fail(message); }
  void finish() {
    if (!in_.at_end()) {
      in_.next("");
      in_.fail("more data than the PLY header declares");
    }
  }

 private:
  TextReader in_;
};

// Binary values: fixed-size numbers in the file's byte order; errors name element and item.
class BinaryValues {
 public:
  BinaryValues(const std::string& path, const std::string& bytes, size_t start, bool big_endian)
      : path_(path),
        bytes_(bytes),
        pos_(start),
        swap_(big_endian != (std::endian::native == std::endian::big)) {}
  void at(const std::string& element, int64_t item) {
    element_ = &element;
    item_ = item;
  }
  double value(Type t, const char* what) {
    const double v = raw(t, what);
    if (!std::isfinite(v))
      fail(std::string("expected ") + what + " to be finite, found " + std::to_string(v));
    return v;
  }
  double attribute(Type t, const std::string& name, IgnoredAttribute& ignored) {
    const double v = raw(t, "a PLY value");
    if (!std::isfinite(v))
      ignored.note(0, "element '" + (element_ ? *element_ : std::string()) + "' item " +
                          std::to_string(item_) + ": property '" + name + "' is " +
                          std::to_string(v));
    return 0;
  }
  [[noreturn]] void fail(const std::string& message) const {
    std::string where =
        element_ ? "element '" + *element_ + "' item " + std::to_string(item_) + ": " : "";
    throw InputError({path_, 0, 0, ""}, where + message);
  }
  void finish() const {
    if (pos_ != bytes_.size()) {
      throw InputError({path_, 0, 0, ""}, std::to_string(bytes_.size() - pos_) +
                                              " bytes after the data the PLY header declares");
    }
  }

 private:
  double raw(Type t, const char* what) {
    const size_t n = size_of(t);
    if (bytes_.size() - pos_ < n)
      fail(std::string("the file ends (truncated?) where ") + what + " was expected");
    unsigned char b[8];
    std::memcpy(b, bytes_.data() + pos_, n);
    pos_ += n;
    if (swap_) std::reverse(b, b + n);
    return decode(t, b);
  }
  static double decode(Type t, const unsigned char* b) {
    auto as = [b]<class T>(T) {
      T v;
      std::memcpy(&v, b, sizeof v);
      return static_cast<double>(v);
    };
    switch (t) {
      case Type::Int8: return as(int8_t{});
      case Type::UInt8: return as(uint8_t{});
      case Type::Int16: return as(int16_t{});
      case Type::UInt16: return as(uint16_t{});
      case Type::Int32: return as(int32_t{});
      case Type::UInt32: return as(uint32_t{});
      case Type::Float32: return as(float{});
      case Type::Float64: return as(double{});
      case Type::None: break;
    }
    return 0.0;
  }
  const std::string& path_;
  const std::string& bytes_;
  size_t pos_;
  bool swap_;
  const std::string* element_ = nullptr;
  int64_t item_ = 0;
};

// Each value read consumes at least one byte or token, so the loops end with the file.
// Positions and face indices are strict; the other values (normals, colours, texture
// coordinates, other elements) are not used, and a bad one is ignored with one warning.
template <class Values>
PolygonSoup read_items(const std::string& path, const Header& h, const Layout& layout, Values& in) {
  PolygonSoup out;
  IgnoredAttribute ignored("PLY values a simulation does not use (normals, colours, ...)");
  const int64_t vertices = h.elements[layout.vertex].count;
  out.positions.reserve(static_cast<size_t>(vertices) * 3);
  out.face_starts.push_back(0);
  for (size_t e = 0; e < h.elements.size(); ++e) {
    const Element& element = h.elements[e];
    for (int64_t item = 0; item < element.count; ++item) {
      in.at(element.name, item);
      double xyz[3] = {0, 0, 0};
      for (size_t p = 0; p < element.properties.size(); ++p) {
        const Property& property = element.properties[p];
        if (!property.is_list()) {
          int axis = -1;
          for (int k = 0; k < 3; ++k)
            if (e == layout.vertex && p == layout.xyz[k]) axis = k;
          if (axis < 0) {
            in.attribute(property.type, property.name, ignored);
          } else {
            xyz[axis] = in.value(property.type, "a vertex coordinate");
          }
          continue;
        }
        const bool face_list = e == layout.face && p == layout.face_list;
        const double n = in.value(property.count_type, "a list length");
        if (n < 0 || n > static_cast<double>(face_list ? kMaxFaceSize : kMaxListLength)) {
          in.fail("a list length of " + std::to_string(static_cast<int64_t>(n)) +
                  " is out of range [0, " +
                  std::to_string(face_list ? kMaxFaceSize : kMaxListLength) + "]");
        }
        if (face_list && n < 3) {
          in.fail("a face needs at least 3 vertex indices, found " +
                  std::to_string(static_cast<int64_t>(n)));
        }
        for (int64_t k = 0; k < static_cast<int64_t>(n); ++k) {
          if (!face_list) {
            in.attribute(property.type, property.name, ignored);
            continue;
          }
          const double v = in.value(property.type, "a vertex index");
          if (v < 0 || v >= static_cast<double>(vertices)) {
            in.fail("vertex index " + std::to_string(static_cast<int64_t>(v)) +
                    " is out of range: the file has " + std::to_string(vertices) +
                    " vertices (0 to " + std::to_string(vertices - 1) + ")");
          }
          out.indices.push_back(static_cast<uint32_t>(v));
        }
        if (face_list) out.face_starts.push_back(static_cast<uint32_t>(out.indices.size()));
      }
      if (e == layout.vertex) out.positions.insert(out.positions.end(), xyz, xyz + 3);
    }
  }
  in.finish();
  warn_ignored(path, {&ignored}, out.warnings);
  return out;
}

}  // namespace

bool is_ply(const std::string& path, const std::string& bytes) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return extension == ".ply" || bytes.rfind("ply", 0) == 0;
}

PolygonSoup read_ply(const std::string& path, const std::string& bytes) {
  const Header header = parse_header(path, bytes);
  const Layout layout = find_layout(path, header);
  check_counts_fit(path, header, bytes.size() - header.data_start);
  if (header.format == "ascii") {
    AsciiValues in(path, bytes, header.lines);
    return read_items(path, header, layout, in);
  }
  BinaryValues in(path, bytes, header.data_start, header.format == "binary_big_endian");
  return read_items(path, header, layout, in);
}

}  // namespace tacta::mesh_detail
