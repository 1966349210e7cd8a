// VTK legacy files (.vtk), ASCII or BINARY (big-endian values from the line after each section's
// header line): DATASET UNSTRUCTURED_GRID (POINTS; CELLS in the classic "count ids..." layout or
// the 5.1 OFFSETS/CONNECTIVITY layout; CELL_TYPES) holds tets, DATASET POLYDATA (POINTS, VERTICES,
// LINES, POLYGONS, TRIANGLE_STRIPS) a surface. A dataset FIELD block and METADATA are skipped;
// attribute data (POINT_DATA, CELL_DATA) ends the reading, nothing there is needed. Facts from
// "VTK File Formats" (Kitware) and vtkDataReader.cxx (type names and sizes, binary layout).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "mesh/volume_readers.hpp"
#include "mesh/surface_readers.hpp"
#include "mesh/text_reader.hpp"
#include "mesh/vtk_cells.hpp"

namespace tacta::mesh_detail {

namespace {

constexpr int64_t kMaxCount = 2'000'000'000;
constexpr int kVtkStrip = 6, kVtkPolygon = 7;  // vtkCellType.h

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

// A value type's size in a BINARY file; vtkidtype is written as a 4-byte int, long as 8 bytes
// (vtkDataReader on 64-bit Linux).
struct LegacyType {
  int size = 0;
  bool is_float = false, is_signed = true;
};

LegacyType legacy_type(const TextReader& in, std::string_view name) {
  struct Named {
    const char* name;
    LegacyType type;
  };
  static constexpr Named kTypes[] = {{"char", {1, false, true}},
                                     {"signed_char", {1, false, true}},
                                     {"unsigned_char", {1, false, false}},
                                     {"short", {2, false, true}},
                                     {"unsigned_short", {2, false, false}},
                                     {"vtkidtype", {4, false, true}},
                                     {"int", {4, false, true}},
                                     {"unsigned_int", {4, false, false}},
                                     {"long", {8, false, true}},
                                     {"unsigned_long", {8, false, false}},
                                     {"vtktypeint64", {8, false, true}},
                                     {"vtktypeuint64", {8, false, false}},
                                     {"float", {4, true, true}},
                                     {"double", {8, true, true}}};
  for (const Named& t : kTypes)
    if (iequals(name, t.name)) return t.type;
  in.fail("unknown VTK data type '" + std::string(name.substr(0, 40)) +
          "' (float, double, int, vtktypeint64, ...)");
}

// The values of one section: tokens in an ASCII file; in a BINARY file, big-endian numbers that
// begin() checks against the file size and steps over (errors then name the section's line).
class LegacyValues {
 public:
  LegacyValues(TextReader& in, bool binary) : in_(in), binary_(binary) {}
  bool binary() const { return binary_; }

  void begin(LegacyType type, int64_t count, const std::string& what) {
    type_ = type;
    if (!binary_) return;
    in_.skip_line();  // the header line's line break; the data follows it
    const size_t left = in_.text().size() - in_.position();
    if (count > 0 && static_cast<uint64_t>(count) > left / static_cast<size_t>(type.size)) {
      in_.fail(what + ": the file ends before its " + std::to_string(count) +
               " binary values (truncated?)");
    }
    data_ = in_.text().data() + in_.position();
    next_ = 0;
    in_.skip_bytes(static_cast<size_t>(count) * static_cast<size_t>(type.size));
  }

  double next_double(const char* what) {
    if (!binary_) return in_.next_double(what);
    double v = decode();
    if (!std::isfinite(v)) in_.fail(std::string(what) + " is NaN or infinite");
    return v;
  }

  int64_t next_int(const char* what) {
    if (!binary_) return in_.next_int(what);
    if (type_.is_float) in_.fail(std::string(what) + " must be an integer type, not a float type");
    double v = decode();
    if (v > 9.2e18) in_.fail(std::string(what) + " is too large");
    return static_cast<int64_t>(v);
  }

  // Skips count values of the current type (an ASCII token each; binary data begin() passed).
  void skip(int64_t count, const char* what) {
    for (int64_t i = 0; i < count && !binary_; ++i) in_.next(what);
  }

 private:
  double decode() {
    const size_t n = static_cast<size_t>(type_.size);
    const unsigned char* p = reinterpret_cast<const unsigned char*>(data_) + next_ * n;
    ++next_;
    uint64_t raw = 0;
    for (size_t i = 0; i < n; ++i) raw = (raw << 8) | p[i];
    if (type_.is_float && n == 4) {
      const uint32_t bits = static_cast<uint32_t>(raw);
      float f;
      std::memcpy(&f, &bits, 4);
      return static_cast<double>(f);
    }
    if (type_.is_float) {
      double d;
      std::memcpy(&d, &raw, 8);
      return d;
    }
    if (type_.is_signed && n < 8 && (raw >> (8 * n - 1)) != 0) raw |= ~uint64_t{0} << (8 * n);
    return type_.is_signed ? static_cast<double>(static_cast<int64_t>(raw))
                           : static_cast<double>(raw);
  }

  TextReader& in_;
  bool binary_;
  LegacyType type_;
  const char* data_ = nullptr;
  size_t next_ = 0;
};

struct LegacyCells {
  std::vector<int64_t> offsets;  // cell c uses connectivity[offsets[c], offsets[c+1])
  std::vector<int64_t> connectivity;
  int line = 0;
  bool present = false;
  size_t count() const { return offsets.empty() ? 0 : offsets.size() - 1; }
};

bool is_keyword(std::string_view token) {
  for (const char* k : {"POINTS", "CELLS", "CELL_TYPES", "POINT_DATA", "CELL_DATA", "FIELD",
                        "METADATA", "VERTICES", "LINES", "POLYGONS", "TRIANGLE_STRIPS"})
    if (iequals(token, k)) return true;
  return false;
}

// METADATA (COMPONENT_NAMES, INFORMATION ...) runs to a blank line (vtkDataReader::ReadMetaData),
// or, in a file written by hand, to the next section.
void skip_metadata(TextReader& in) {
  in.skip_line();
  for (;;) {
    const std::string_view rest = in.text().substr(in.position());
    if (rest.empty()) return;
    const std::string_view line = rest.substr(0, rest.find('\n'));
    const size_t word = line.find_first_not_of(" \t\r");
    if (word == std::string_view::npos) {
      in.skip_line();
      return;
    }
    if (is_keyword(line.substr(word, line.find_first_of(" \t\r", word) - word))) return;
    in.skip_line();
  }
}

void read_points(TextReader& in, LegacyValues& values, std::vector<double>& positions) {
  const int64_t count = in.next_int_in("the point count", 0, kMaxCount);
  values.begin(legacy_type(in, in.next("the point data type")), 3 * count, "POINTS");
  positions.clear();
  for (int64_t i = 0; i < 3 * count; ++i) {
    if (!values.binary() && is_keyword(in.peek())) {
      in.next("");
      in.fail("POINTS says " + std::to_string(count) + " points but only " + std::to_string(i) +
              " coordinates (not " + std::to_string(3 * count) + ") are given");
    }
    positions.push_back(values.next_double("a point coordinate"));
  }
}

void read_classic_cells(TextReader& in, LegacyValues& values, LegacyCells& cells, int64_t count,
                        int64_t size, const std::string& name) {
  values.begin({4, false, true}, size, name);  // "count ids..." as 4-byte ints
  cells.offsets.assign(1, 0);
  int64_t used = 0;
  for (int64_t c = 0; c < count; ++c) {
    if (used >= size)
      in.fail(name + " says its cell list holds " + std::to_string(size) + " numbers, cell " +
              std::to_string(c) + " goes past that");
    const int64_t n = values.next_int("a cell's point count");
    if (n < 0 || n > 1'000'000 || used + n + 1 > size) {
      in.fail(name + " says its cell list holds " + std::to_string(size) + " numbers, cell " +
              std::to_string(c) + " (of " + std::to_string(n) + " points) goes past that");
    }
    used += n + 1;
    for (int64_t k = 0; k < n; ++k)
      cells.connectivity.push_back(values.next_int("a cell point index"));
    cells.offsets.push_back(static_cast<int64_t>(cells.connectivity.size()));
  }
  if (used != size)
    in.fail(name + " says its cell list holds " + std::to_string(size) +
            " numbers, the cells use " + std::to_string(used));
}

void read_offset_cells(TextReader& in, LegacyValues& values, LegacyCells& cells,
                       int64_t offset_count, int64_t connectivity_count) {
  in.expect("OFFSETS");
  values.begin(legacy_type(in, in.next("the offset data type")), offset_count, "OFFSETS");
  cells.offsets.clear();
  for (int64_t i = 0; i < offset_count; ++i)
    cells.offsets.push_back(values.next_int("a cell offset"));
  in.expect("CONNECTIVITY");
  values.begin(legacy_type(in, in.next("the connectivity data type")), connectivity_count,
               "CONNECTIVITY");
  for (int64_t i = 0; i < connectivity_count; ++i)
    cells.connectivity.push_back(values.next_int("a cell point index"));
  if (cells.offsets.empty() || cells.offsets.front() != 0 ||
      cells.offsets.back() != connectivity_count) {
    in.fail("OFFSETS must start at 0 and end at the connectivity size " +
            std::to_string(connectivity_count));
  }
  for (size_t i = 1; i < cells.offsets.size(); ++i) {
    if (cells.offsets[i] < cells.offsets[i - 1])
      in.fail("OFFSETS must not decrease (offset " + std::to_string(i) + ")");
  }
}

// "CELLS a b", "POLYGONS a b", ...: classic (a cells, b numbers) or, when OFFSETS follows,
// the 5.1 layout (a offsets, b connectivity entries).
void read_cells(TextReader& in, LegacyValues& values, LegacyCells& cells,
                std::string_view keyword) {
  const std::string name(keyword.substr(0, 40));
  if (cells.present) in.fail(name + " is given twice");
  cells.present = true;
  cells.line = in.line();
  const int64_t a = in.next_int_in("the cell count", 0, kMaxCount);
  const int64_t b = in.next_int_in("the cell list size", 0, kMaxCount);
  const std::string_view rest = in.text().substr(in.position());
  const size_t start = rest.find_first_not_of(" \t\r\n");
  if (start != std::string_view::npos && rest.substr(start).starts_with("OFFSETS")) {
    read_offset_cells(in, values, cells, a, b);
  } else {
    read_classic_cells(in, values, cells, a, b, name);
  }
}

// A dataset FIELD block of numeric arrays: "FIELD name n", then per array "name components tuples
// type" and the values (and METADATA, when VTK wrote some).
void skip_field(TextReader& in, LegacyValues& values) {
  in.next("the FIELD name");
  const int64_t arrays = in.next_int_in("the FIELD array count", 0, 100'000);
  for (int64_t a = 0; a < arrays; ++a) {
    in.next("a FIELD array name");
    const int64_t components = in.next_int_in("a FIELD array's component count", 1, 1'000'000);
    const int64_t tuples = in.next_int_in("a FIELD array's tuple count", 0, kMaxCount);
    const std::string_view type = in.next("a FIELD array's data type");
    if (iequals(type, "string") || iequals(type, "utf8_string") || iequals(type, "variant") ||
        iequals(type, "bit")) {
      in.fail("a FIELD array of type '" + std::string(type) +
              "' before the geometry is not supported (numeric arrays are)");
    }
    values.begin(legacy_type(in, type), components * tuples, "FIELD array");
    values.skip(components * tuples, "a FIELD value");
    if (iequals(in.peek(), "METADATA")) {
      in.next("");
      skip_metadata(in);
    }
  }
}

struct Sections {
  std::vector<double> positions;
  bool has_points = false;
  LegacyCells cells, vertices, lines, polygons, strips;
  std::vector<int64_t> types;
  bool has_types = false;
  int types_line = 0;
};

// Every section up to the attribute data; `polydata` picks which sections the dataset may have.
Sections read_sections(TextReader& in, LegacyValues& values, bool polydata) {
  Sections s;
  const char* expected = polydata ? "POINTS, VERTICES, LINES, POLYGONS or TRIANGLE_STRIPS"
                                  : "POINTS, CELLS or CELL_TYPES";
  while (!in.at_end() && !(!polydata && s.has_points && s.cells.present && s.has_types)) {
    const std::string_view keyword = in.next(expected);
    if (iequals(keyword, "POINTS")) {
      if (s.has_points) in.fail("POINTS is given twice");
      read_points(in, values, s.positions);
      s.has_points = true;
    } else if (!polydata && iequals(keyword, "CELLS")) {
      read_cells(in, values, s.cells, keyword);
    } else if (!polydata && iequals(keyword, "CELL_TYPES")) {
      if (s.has_types) in.fail("CELL_TYPES is given twice");
      s.types_line = in.line();
      const int64_t count = in.next_int_in("the cell type count", 0, kMaxCount);
      values.begin({4, false, true}, count, "CELL_TYPES");
      for (int64_t i = 0; i < count; ++i) s.types.push_back(values.next_int("a cell type"));
      s.has_types = true;
    } else if (polydata && iequals(keyword, "VERTICES")) {
      read_cells(in, values, s.vertices, keyword);
    } else if (polydata && iequals(keyword, "LINES")) {
      read_cells(in, values, s.lines, keyword);
    } else if (polydata && iequals(keyword, "POLYGONS")) {
      read_cells(in, values, s.polygons, keyword);
    } else if (polydata && iequals(keyword, "TRIANGLE_STRIPS")) {
      read_cells(in, values, s.strips, keyword);
    } else if (iequals(keyword, "METADATA")) {
      skip_metadata(in);
    } else if (iequals(keyword, "FIELD")) {
      skip_field(in, values);
    } else if (iequals(keyword, "POINT_DATA") || iequals(keyword, "CELL_DATA")) {
      break;
    } else {
      in.fail(std::string("expected ") + expected + ", found '" +
              std::string(keyword.substr(0, 40)) + "'");
    }
  }
  if (!s.has_points) in.fail("the file has no POINTS section");
  return s;
}

struct Header {
  bool binary = false;
  bool polydata = false;
};

Header read_header(TextReader& in) {
  in.expect("#");
  in.skip_line();  // "# vtk DataFile Version x.y"
  in.skip_line();  // title, free text
  Header h;
  const std::string_view encoding = in.next("ASCII or BINARY");
  h.binary = iequals(encoding, "BINARY");
  if (!h.binary && !iequals(encoding, "ASCII"))
    in.fail("expected ASCII or BINARY on line 3, found '" + std::string(encoding.substr(0, 40)) +
            "'");
  const std::string_view dataset_keyword = in.next("'DATASET'");
  if (!iequals(dataset_keyword, "DATASET"))
    in.fail("expected 'DATASET', found '" + std::string(dataset_keyword.substr(0, 40)) + "'");
  const std::string_view dataset = in.next("the dataset type");
  h.polydata = iequals(dataset, "POLYDATA");
  if (!h.polydata && !iequals(dataset, "UNSTRUCTURED_GRID")) {
    in.fail("DATASET " + std::string(dataset.substr(0, 40)) +
            " is not read: UNSTRUCTURED_GRID holds tetrahedra, POLYDATA a surface");
  }
  return h;
}

}  // namespace

VolumeMesh read_vtk_legacy(const std::string& path, std::string_view text, LoadReport& report) {
  TextReader in(path, text);
  report.format = "vtk-legacy";
  const Header header = read_header(in);
  if (header.polydata)
    in.fail("DATASET POLYDATA is a surface, not tetrahedra: load it as a surface mesh");
  LegacyValues values(in, header.binary);
  Sections s = read_sections(in, values, false);
  if (!s.cells.present) in.fail("the file has no CELLS section");
  if (!s.has_types) in.fail("the file has no CELL_TYPES section");
  const size_t cell_count = s.cells.count();
  if (s.types.size() != cell_count) {
    in.fail_at(s.types_line, "CELL_TYPES lists " + std::to_string(s.types.size()) + " types for " +
                                 std::to_string(cell_count) + " cells");
  }
  VolumeMesh out;
  out.source = path;
  out.positions = std::move(s.positions);
  const size_t points = out.positions.size() / 3;
  std::vector<int64_t> tet;
  for (size_t c = 0; c < cell_count; ++c) {
    tet.assign(s.cells.connectivity.begin() + s.cells.offsets[c],
               s.cells.connectivity.begin() + s.cells.offsets[c + 1]);
    check_vtk_cell(path, s.cells.line, c, s.types[c], tet, points);
    if (s.types[c] != kVtkTetra) {
      ++report.skipped_elements;
      continue;
    }
    for (int64_t index : tet) out.tets.push_back(static_cast<uint32_t>(index));
  }
  return out;
}

void add_vtk_polygons(const std::string& path, int line, const std::vector<int64_t>& offsets,
                      const std::vector<int64_t>& connectivity, bool strips, size_t first_point,
                      PolygonSoup& out) {
  const size_t points = out.positions.size() / 3 - first_point;
  std::vector<int64_t> cell;
  for (size_t c = 0; c + 1 < offsets.size(); ++c) {
    cell.assign(connectivity.begin() + offsets[c], connectivity.begin() + offsets[c + 1]);
    check_vtk_cell(path, line, c, strips ? kVtkStrip : kVtkPolygon, cell, points);
    if (cell.size() < 3) {
      throw InputError({path, line, 0, ""},
                       std::string(strips ? "strip " : "polygon ") + std::to_string(c) + " has " +
                           std::to_string(cell.size()) + " points; it needs at least 3");
    }
    if (out.indices.size() + 3 * cell.size() > 4'000'000'000ull)
      throw InputError({path, line, 0, ""}, "more polygon corners than a mesh can index");
    if (!strips) {
      for (int64_t i : cell)
        out.indices.push_back(static_cast<uint32_t>(first_point + static_cast<size_t>(i)));
      out.face_starts.push_back(static_cast<uint32_t>(out.indices.size()));
      continue;
    }
    // Triangle k of a strip is (k, k+1, k+2), with the first two swapped for odd k so that every
    // triangle keeps the strip's winding (vtkTriangleStrip::DecomposeStrip).
    for (size_t k = 0; k + 2 < cell.size(); ++k) {
      const size_t a = k % 2 == 0 ? k : k + 1, b = k % 2 == 0 ? k + 1 : k;
      for (size_t corner : {a, b, k + 2})
        out.indices.push_back(
            static_cast<uint32_t>(first_point + static_cast<size_t>(cell[corner])));
      out.face_starts.push_back(static_cast<uint32_t>(out.indices.size()));
    }
  }
}

void warn_ignored_cells(size_t vertices, size_t lines, PolygonSoup& out) {
  if (vertices + lines == 0) return;
  out.warnings.push_back(std::to_string(vertices) + " vertex cells and " + std::to_string(lines) +
                         " line cells were ignored: a body's surface is its polygons and strips");
}

PolygonSoup read_vtk_legacy_polydata(const std::string& path, const std::string& bytes) {
  TextReader in(path, bytes);
  const Header header = read_header(in);
  if (!header.polydata)
    in.fail("DATASET UNSTRUCTURED_GRID holds cells, not a surface: load it as a volume mesh");
  LegacyValues values(in, header.binary);
  Sections s = read_sections(in, values, true);
  PolygonSoup out;
  out.positions = std::move(s.positions);
  out.face_starts.push_back(0);
  add_vtk_polygons(path, s.polygons.line, s.polygons.offsets, s.polygons.connectivity, false, 0,
                   out);
  add_vtk_polygons(path, s.strips.line, s.strips.offsets, s.strips.connectivity, true, 0, out);
  warn_ignored_cells(s.vertices.count(), s.lines.count(), out);
  return out;
}

}  // namespace tacta::mesh_detail
