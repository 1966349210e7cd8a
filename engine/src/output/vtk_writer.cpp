#include "tacta/output/vtk_writer.hpp"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>
#include <type_traits>
#include <vector>

#include "tacta/error.hpp"

namespace tacta::output {

namespace {

// VTK cell type ids (vtkCellType.h): fixed by the file format.
constexpr uint8_t kVtkTriangle = 5;
constexpr uint8_t kVtkQuad = 9;
constexpr uint8_t kVtkTetra = 10;

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what) {
  throw InputError(SourceLocation{file.string(), 0, 0, ""}, what);
}

std::string base64(const uint8_t* bytes, size_t count) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((count + 2) / 3 * 4);
  for (size_t i = 0; i < count; i += 3) {
    const uint32_t b0 = bytes[i];
    const uint32_t b1 = i + 1 < count ? bytes[i + 1] : 0;
    const uint32_t b2 = i + 2 < count ? bytes[i + 2] : 0;
    const uint32_t triple = (b0 << 16) | (b1 << 8) | b2;
    out += kAlphabet[(triple >> 18) & 63];
    out += kAlphabet[(triple >> 12) & 63];
    out += i + 1 < count ? kAlphabet[(triple >> 6) & 63] : '=';
    out += i + 2 < count ? kAlphabet[triple & 63] : '=';
  }
  return out;
}

// One DataArray element. Binary: a UInt64 byte count then the raw little-endian values, base64
// encoded as one stream (as VTK's own writer does for uncompressed inline data).
template <typename T>
void write_array(std::ostream& os, const char* type, const std::string& name, int components,
                 const T* values, size_t count, VtkEncoding encoding, const char* indent) {
  os << indent << "<DataArray type=\"" << type << "\"";
  if (!name.empty()) os << " Name=\"" << name << "\"";
  if (components > 1) os << " NumberOfComponents=\"" << components << "\"";
  os << " format=\"" << (encoding == VtkEncoding::Ascii ? "ascii" : "binary") << "\">\n";
  if (encoding == VtkEncoding::Ascii) {
    os << indent << "  ";
    char text[32];
    for (size_t i = 0; i < count; ++i) {
      if constexpr (std::is_floating_point_v<T>)
        std::snprintf(text, sizeof text, "%.17g",
                      static_cast<double>(values[i]));  // exact round trip
      else
        std::snprintf(text, sizeof text, "%lld", static_cast<long long>(values[i]));
      os << text;
      if (i + 1 < count) {
        if ((i + 1) % 12 == 0)
          os << "\n" << indent << "  ";  // 12 values a line
        else
          os << ' ';
      }
    }
    os << "\n";
  } else {
    const uint64_t byte_count = count * sizeof(T);
    std::vector<uint8_t> block(sizeof byte_count + byte_count);
    std::memcpy(block.data(), &byte_count, sizeof byte_count);  // x86-64 and ARM64: little endian
    if (byte_count > 0) std::memcpy(block.data() + sizeof byte_count, values, byte_count);
    os << indent << "  " << base64(block.data(), block.size()) << "\n";
  }
  os << indent << "</DataArray>\n";
}

void check_field(const std::filesystem::path& file, const VtkField& field, size_t count,
                 const char* where) {
  if (field.name.empty() || field.name.find_first_of("\"<>&") != std::string::npos)
    fail(file, std::string(where) + " field name \"" + field.name + "\" is empty or not XML-safe");
  if (field.components < 1 || field.components > 9)
    fail(file, std::string(where) + " field \"" + field.name + "\" has " +
                   std::to_string(field.components) + " components; expected 1 to 9");
  const size_t expected = count * static_cast<size_t>(field.components);
  if (field.values.size() != expected)
    fail(file, std::string(where) + " field \"" + field.name + "\" has " +
                   std::to_string(field.values.size()) + " values; expected " +
                   std::to_string(expected) + " (" + std::to_string(count) + " x " +
                   std::to_string(field.components) + ")");
}

void check_indices(const std::filesystem::path& file, std::span<const uint32_t> indices,
                   size_t per_cell, size_t point_count, const char* kind) {
  if (indices.size() % per_cell != 0)
    fail(file, std::string(kind) + " hold " + std::to_string(indices.size()) +
                   " indices; expected a multiple of " + std::to_string(per_cell));
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices[i] >= point_count)
      fail(file, std::string(kind) + " index " + std::to_string(indices[i]) + " (entry " +
                     std::to_string(i) + ") is past the " + std::to_string(point_count) +
                     " points");
}

void write_fields(std::ostream& os, const char* element, const std::vector<VtkField>& fields,
                  VtkEncoding encoding) {
  os << "      <" << element << ">\n";
  for (const VtkField& f : fields)
    write_array(os, "Float64", f.name, f.components, f.values.data(), f.values.size(), encoding,
                "        ");
  os << "      </" << element << ">\n";
}

}  // namespace

VtkGrid grid_of(const VolumeMesh& mesh, std::span<const double> current_positions) {
  VtkGrid grid;
  grid.points =
      current_positions.empty() ? std::span<const double>(mesh.positions) : current_positions;
  if (!mesh.tets.empty())
    grid.tets = mesh.tets;
  else if (!mesh.quads.empty())
    grid.quads = mesh.quads;
  else
    grid.triangles = mesh.triangles;
  return grid;
}

void write_vtu(const std::filesystem::path& file, const VtkGrid& grid, VtkEncoding encoding) {
  if (grid.points.size() % 3 != 0)
    fail(file, "points hold " + std::to_string(grid.points.size()) + " values; expected 3 a point");
  const size_t point_count = grid.points.size() / 3;
  check_indices(file, grid.tets, 4, point_count, "tets");
  check_indices(file, grid.quads, 4, point_count, "quads");
  check_indices(file, grid.triangles, 3, point_count, "triangles");
  const size_t cell_count =
      grid.tets.size() / 4 + grid.quads.size() / 4 + grid.triangles.size() / 3;
  for (const VtkField& f : grid.point_data) check_field(file, f, point_count, "point");
  for (const VtkField& f : grid.cell_data) check_field(file, f, cell_count, "cell");

  std::vector<int64_t> connectivity;
  std::vector<int64_t> offsets;
  std::vector<uint8_t> types;
  connectivity.reserve(grid.tets.size() + grid.quads.size() + grid.triangles.size());
  offsets.reserve(cell_count);
  types.reserve(cell_count);
  auto add_cells = [&](std::span<const uint32_t> indices, size_t per_cell, uint8_t type) {
    for (size_t c = 0; c + per_cell <= indices.size(); c += per_cell) {
      for (size_t k = 0; k < per_cell; ++k) connectivity.push_back(indices[c + k]);
      offsets.push_back(static_cast<int64_t>(connectivity.size()));
      types.push_back(type);
    }
  };
  add_cells(grid.tets, 4, kVtkTetra);
  add_cells(grid.quads, 4, kVtkQuad);
  add_cells(grid.triangles, 3, kVtkTriangle);

  std::ostringstream os;
  os << "<?xml version=\"1.0\"?>\n"
     << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
        "header_type=\"UInt64\">\n"
     << "  <UnstructuredGrid>\n"
     << "    <Piece NumberOfPoints=\"" << point_count << "\" NumberOfCells=\"" << cell_count
     << "\">\n";
  write_fields(os, "PointData", grid.point_data, encoding);
  write_fields(os, "CellData", grid.cell_data, encoding);
  os << "      <Points>\n";
  write_array(os, "Float64", "Points", 3, grid.points.data(), grid.points.size(), encoding,
              "        ");
  os << "      </Points>\n      <Cells>\n";
  write_array(os, "Int64", "connectivity", 1, connectivity.data(), connectivity.size(), encoding,
              "        ");
  write_array(os, "Int64", "offsets", 1, offsets.data(), offsets.size(), encoding, "        ");
  write_array(os, "UInt8", "types", 1, types.data(), types.size(), encoding, "        ");
  os << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";

  if (file.has_parent_path()) {
    std::error_code ignored;
    std::filesystem::create_directories(file.parent_path(), ignored);
  }
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << os.str();
  if (!out) fail(file, "cannot write the file (directory missing or not writable?)");
}

VtkSeries::VtkSeries(std::filesystem::path directory, std::string name, VtkEncoding encoding)
    : directory_(std::move(directory)),
      name_(std::move(name)),
      encoding_(encoding),
      pvd_file_(directory_ / (name_ + ".pvd")) {}

std::filesystem::path VtkSeries::write(double time_s, const VtkGrid& grid) {
  char step[32];
  std::snprintf(step, sizeof step, "_%06zu.vtu", steps_.size());
  const std::string relative = name_ + step;
  const std::filesystem::path file = directory_ / relative;
  write_vtu(file, grid, encoding_);
  steps_.push_back({time_s, relative});
  write_pvd();
  return file;
}

void VtkSeries::write_pvd() const {
  std::ostringstream os;
  os << "<?xml version=\"1.0\"?>\n"
     << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
     << "  <Collection>\n";
  char time[40];
  for (const Step& s : steps_) {
    std::snprintf(time, sizeof time, "%.17g", s.time_s);
    os << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\"0\" file=\"" << s.file
       << "\"/>\n";
  }
  os << "  </Collection>\n</VTKFile>\n";
  std::ofstream out(pvd_file_, std::ios::binary | std::ios::trunc);
  out << os.str();
  if (!out) fail(pvd_file_, "cannot write the collection file");
}

}  // namespace tacta::output
