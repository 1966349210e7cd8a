#include "mesh/ply_check.hpp"

#include <algorithm>
#include <cstdint>
#include <sstream>
#include <vector>

#include "mesh/text_reader.hpp"
#include "tacta/error.hpp"

namespace tacta::mesh_detail {

namespace {

struct PlyProperty {
  int size = 0;        // bytes of a fixed property, or of each list item
  int count_size = 0;  // bytes of a list's count; 0 for a fixed property
};

struct PlyElement {
  int64_t count = 0;
  std::vector<PlyProperty> properties;
};

int type_size(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32") return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

uint64_t read_count(const std::string& bytes, size_t pos, int size, bool big_endian) {
  uint64_t value = 0;
  for (int i = 0; i < size; ++i) {
    int byte = big_endian ? i : size - 1 - i;
    value = (value << 8) | static_cast<unsigned char>(bytes[pos + static_cast<size_t>(byte)]);
  }
  return value;
}

}  // namespace

void check_ply_complete(const std::string& path) {
  const std::string bytes = read_file_bytes(path);
  if (bytes.rfind("ply", 0) != 0) return;
  auto fail = [&](int line, const std::string& message) { throw InputError({path, line, 0, ""}, message); };
  const size_t header_end = bytes.find("end_header");
  if (header_end == std::string::npos) fail(0, "the PLY header has no end_header line (truncated?)");
  size_t body = bytes.find('\n', header_end);
  if (body == std::string::npos) fail(0, "the PLY file ends after its header (truncated?)");
  ++body;

  std::istringstream header(bytes.substr(0, header_end));
  std::string line, format;
  std::vector<PlyElement> elements;
  int header_lines = 1;  // the end_header line itself
  for (int number = 1; std::getline(header, line); ++number, ++header_lines) {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "format") {
      words >> format;
    } else if (keyword == "element") {
      std::string name;
      PlyElement e;
      if (!(words >> name >> e.count) || e.count < 0 || e.count > 2'000'000'000) fail(number, "bad PLY element line");
      elements.push_back(e);
    } else if (keyword == "property") {
      if (elements.empty()) fail(number, "a PLY property before any element");
      std::string type;
      words >> type;
      PlyProperty p;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        p.count_size = type_size(count_type);
        p.size = type_size(item_type);
        if (p.count_size == 0 || p.size == 0) fail(number, "unknown PLY list types '" + count_type + "', '" + item_type + "'");
      } else {
        p.size = type_size(type);
        if (p.size == 0) fail(number, "unknown PLY property type '" + type + "'");
      }
      elements.back().properties.push_back(p);
    }
  }
  if (format == "ascii") {
    TextReader in(path, std::string_view(bytes).substr(body));
    try {
      for (const PlyElement& e : elements) {
        for (int64_t item = 0; item < e.count; ++item) {
          for (const PlyProperty& p : e.properties) {
            int64_t n = p.count_size ? in.next_int_in("a PLY list length", 0, 1'000'000) : 1;
            for (int64_t k = 0; k < n; ++k) in.next_double("a PLY value");
          }
        }
      }
    } catch (const InputError& e) {
      // The reader counted lines from the end of the header: give the file's line.
      fail(e.where().line + header_lines, std::string(e.what()).substr(std::string(e.what()).find(": ") + 2));
    }
  } else if (format == "binary_little_endian" || format == "binary_big_endian") {
    const bool big_endian = format == "binary_big_endian";
    size_t pos = body;
    for (const PlyElement& e : elements) {
      for (int64_t item = 0; item < e.count; ++item) {
        for (const PlyProperty& p : e.properties) {
          uint64_t n = 1;
          if (p.count_size) {
            if (pos + static_cast<size_t>(p.count_size) > bytes.size()) fail(0, "the PLY data is shorter than its header says (truncated?)");
            n = read_count(bytes, pos, p.count_size, big_endian);
            pos += static_cast<size_t>(p.count_size);
          }
          if (n > bytes.size() || pos + n * static_cast<size_t>(p.size) > bytes.size()) {
            fail(0, "the PLY data is shorter than its header says (truncated?)");
          }
          pos += n * static_cast<size_t>(p.size);
        }
      }
    }
  } else {
    fail(2, "unknown PLY format '" + format + "' (ascii, binary_little_endian, binary_big_endian)");
  }
}

}  // namespace tacta::mesh_detail
