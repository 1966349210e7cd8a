// VTK XML files through tinyxml2 (DataArrays: see vtk_xml_data.hpp): UnstructuredGrid (.vtu)
// gives tets, PolyData (.vtp) a surface of polygons and triangle strips.
#include <cstring>
#include <string>
#include <tinyxml2.h>
#include <vector>

#include "mesh/volume_readers.hpp"
#include "mesh/surface_readers.hpp"
#include "mesh/vtk_cells.hpp"
#include "mesh/vtk_xml_data.hpp"

namespace tacta::mesh_detail {

namespace {

using tinyxml2::XMLElement;

// The piece's points, appended to positions; returns how many.
size_t read_points(const XmlContext& ctx, const XMLElement* piece, std::vector<double>& positions) {
  const size_t points = static_cast<size_t>(count_attribute(ctx, piece, "NumberOfPoints"));
  if (points == 0 && piece->FirstChildElement("Points") == nullptr) return 0;
  const XMLElement* point_array = child(ctx, child(ctx, piece, "Points"), "DataArray");
  if (point_array->IntAttribute("NumberOfComponents", 1) != 3)
    ctx.fail(point_array, "point coordinates need NumberOfComponents=\"3\"");
  const std::vector<double> xyz = read_array(ctx, point_array, 3 * points);
  positions.insert(positions.end(), xyz.begin(), xyz.end());
  return points;
}

void read_grid_piece(const XmlContext& ctx, const XMLElement* piece, VolumeMesh& out,
                     LoadReport& report) {
  const size_t cells = static_cast<size_t>(count_attribute(ctx, piece, "NumberOfCells"));
  const size_t first_point = out.positions.size() / 3;
  const size_t points = read_points(ctx, piece, out.positions);
  const XMLElement* cell_node = child(ctx, piece, "Cells");
  const XMLElement* types_array = nullptr;
  for (const XMLElement* a = cell_node->FirstChildElement("DataArray"); a && !types_array;
       a = a->NextSiblingElement("DataArray")) {
    const char* n = a->Attribute("Name");
    if (n && std::strcmp(n, "types") == 0) types_array = a;
  }
  if (!types_array) ctx.fail(cell_node, "<Cells> has no DataArray named 'types'");
  const XmlCells c = read_cells(ctx, cell_node, cells);
  const std::vector<double> types = read_array(ctx, types_array, cells);
  std::vector<int64_t> indices;
  for (size_t i = 0; i < cells; ++i) {
    indices.assign(c.connectivity.begin() + c.offsets[i],
                   c.connectivity.begin() + c.offsets[i + 1]);
    const int64_t type = types[i] >= 0 && types[i] <= 255 ? static_cast<int64_t>(types[i]) : -1;
    check_vtk_cell(ctx.path, c.line, i, type, indices, points);
    if (type != kVtkTetra) {
      ++report.skipped_elements;
      continue;
    }
    for (int64_t index : indices)
      out.tets.push_back(static_cast<uint32_t>(first_point + static_cast<size_t>(index)));
  }
}

// Calls read(piece) for every <Piece> of the dataset element `name`; a dataset needs one.
template <class Read>
void for_each_piece(const XmlContext& ctx, const XMLElement* root, const char* name, Read read) {
  const XMLElement* data = child(ctx, root, name);
  int pieces = 0;
  for (const XMLElement* piece = data->FirstChildElement("Piece"); piece;
       piece = piece->NextSiblingElement("Piece")) {
    read(piece);
    ++pieces;
  }
  if (pieces == 0) ctx.fail(data, std::string("<") + name + "> has no <Piece>");
}

}  // namespace

VolumeMesh read_vtk_xml(const std::string& path, const std::string& text, LoadReport& report) {
  report.format = "vtk-xml";
  tinyxml2::XMLDocument doc;
  XmlContext ctx;
  const XMLElement* root =
      parse_vtk_xml(path, text, "UnstructuredGrid", "tetrahedra (PolyData is a surface)", doc, ctx);
  VolumeMesh out;
  out.source = path;
  for_each_piece(ctx, root, "UnstructuredGrid",
                 [&](const XMLElement* piece) { read_grid_piece(ctx, piece, out, report); });
  return out;
}

PolygonSoup read_vtk_xml_polydata(const std::string& path, const std::string& bytes) {
  tinyxml2::XMLDocument doc;
  XmlContext ctx;
  const XMLElement* root =
      parse_vtk_xml(path, bytes, "PolyData", "a surface (UnstructuredGrid holds cells)", doc, ctx);
  PolygonSoup out;
  out.face_starts.push_back(0);
  size_t vertices = 0, lines = 0;
  for_each_piece(ctx, root, "PolyData", [&](const XMLElement* piece) {
    const size_t first_point = out.positions.size() / 3;
    read_points(ctx, piece, out.positions);
    vertices += static_cast<size_t>(count_attribute(ctx, piece, "NumberOfVerts", true));
    lines += static_cast<size_t>(count_attribute(ctx, piece, "NumberOfLines", true));
    for (const bool strips : {false, true}) {
      const char* count_name = strips ? "NumberOfStrips" : "NumberOfPolys";
      const size_t count = static_cast<size_t>(count_attribute(ctx, piece, count_name, true));
      if (count == 0) continue;
      const XmlCells c = read_cells(ctx, child(ctx, piece, strips ? "Strips" : "Polys"), count);
      add_vtk_polygons(path, c.line, c.offsets, c.connectivity, strips, first_point, out);
    }
  });
  warn_ignored_cells(vertices, lines, out);
  return out;
}

}  // namespace tacta::mesh_detail
