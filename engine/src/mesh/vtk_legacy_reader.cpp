// VTK legacy ASCII files, DATASET UNSTRUCTURED_GRID: POINTS, CELLS (the classic "count ids..."
// layout and the 5.1 OFFSETS/CONNECTIVITY layout) and CELL_TYPES. Attribute data that follows
// (POINT_DATA, CELL_DATA) is not needed and not read. Facts from "VTK File Formats" (Kitware).
#include <string>
#include <vector>

#include "mesh/readers.hpp"
#include "mesh/text_reader.hpp"
#include "mesh/vtk_cells.hpp"

namespace tacta::mesh_detail {

namespace {

constexpr int64_t kMaxCount = 2'000'000'000;

struct LegacyCells {
  std::vector<int64_t> offsets;  // cell c uses connectivity[offsets[c], offsets[c+1])
  std::vector<int64_t> connectivity;
  int line = 0;
};

void read_points(TextReader& in, std::vector<double>& positions) {
  int64_t count = in.next_int_in("the point count", 0, kMaxCount);
  in.next("the point data type");
  positions.clear();
  for (int64_t i = 0; i < 3 * count; ++i) {
    std::string_view next = in.peek();
    if (next == "CELLS" || next == "CELL_TYPES" || next == "POINT_DATA" || next == "METADATA") {
      in.next("");
      in.fail("POINTS says " + std::to_string(count) + " points but only " + std::to_string(i) +
              " coordinates (not " + std::to_string(3 * count) + ") are given");
    }
    positions.push_back(in.next_double("a point coordinate"));
  }
}

void read_classic_cells(TextReader& in, LegacyCells& cells, int64_t count, int64_t size) {
  cells.offsets.assign(1, 0);
  int64_t used = 0;
  for (int64_t c = 0; c < count; ++c) {
    int64_t n = in.next_int_in("a cell's point count", 0, 1'000'000);
    used += n + 1;
    if (used > size)
      in.fail("CELLS says the cell list holds " + std::to_string(size) + " numbers, cell " +
              std::to_string(c) + " goes past that");
    for (int64_t k = 0; k < n; ++k) cells.connectivity.push_back(in.next_int("a cell point index"));
    cells.offsets.push_back(static_cast<int64_t>(cells.connectivity.size()));
  }
  if (used != size)
    in.fail("CELLS says the cell list holds " + std::to_string(size) + " numbers, the cells use " +
            std::to_string(used));
}

void read_offset_cells(TextReader& in, LegacyCells& cells, int64_t offset_count,
                       int64_t connectivity_count) {
  in.expect("OFFSETS");
  in.next("the offset data type");
  cells.offsets.clear();
  for (int64_t i = 0; i < offset_count; ++i) cells.offsets.push_back(in.next_int("a cell offset"));
  in.expect("CONNECTIVITY");
  in.next("the connectivity data type");
  for (int64_t i = 0; i < connectivity_count; ++i)
    cells.connectivity.push_back(in.next_int("a cell point index"));
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

bool is_keyword(std::string_view token) {
  return token == "POINTS" || token == "CELLS" || token == "CELL_TYPES" || token == "POINT_DATA" ||
         token == "CELL_DATA" || token == "FIELD";
}

}  // namespace

VolumeMesh read_vtk_legacy(const std::string& path, std::string_view text, LoadReport& report) {
  TextReader in(path, text);
  report.format = "vtk-legacy";
  in.expect("#");
  in.skip_line();  // "# vtk DataFile Version x.y"
  in.skip_line();  // title, free text
  std::string_view encoding = in.next("ASCII or BINARY");
  if (encoding == "BINARY")
    in.fail("binary legacy VTK files are not supported; save as ASCII or .vtu");
  if (encoding != "ASCII")
    in.fail("expected ASCII or BINARY on line 3, found '" + std::string(encoding.substr(0, 40)) +
            "'");
  in.expect("DATASET");
  std::string_view dataset = in.next("the dataset type");
  if (dataset != "UNSTRUCTURED_GRID") {
    in.fail("only DATASET UNSTRUCTURED_GRID holds tetrahedra, found '" +
            std::string(dataset.substr(0, 40)) + "'");
  }

  VolumeMesh out;
  out.source = path;
  LegacyCells cells;
  std::vector<int64_t> types;
  bool has_points = false, has_cells = false, has_types = false;
  int types_line = 0;
  while (!in.at_end() && !(has_points && has_cells && has_types)) {
    std::string_view keyword = in.next("POINTS, CELLS or CELL_TYPES");
    if (keyword == "POINTS") {
      read_points(in, out.positions);
      has_points = true;
    } else if (keyword == "CELLS") {
      cells.line = in.line();
      int64_t a = in.next_int_in("the cell count", 0, kMaxCount);
      int64_t b = in.next_int_in("the cell list size", 0, kMaxCount);
      if (in.peek() == "OFFSETS") {
        read_offset_cells(in, cells, a, b);
      } else {
        read_classic_cells(in, cells, a, b);
      }
      has_cells = true;
    } else if (keyword == "CELL_TYPES") {
      types_line = in.line();
      int64_t count = in.next_int_in("the cell type count", 0, kMaxCount);
      for (int64_t i = 0; i < count; ++i) types.push_back(in.next_int("a cell type"));
      has_types = true;
    } else if (keyword == "METADATA") {
      while (!in.at_end() && !is_keyword(in.peek())) in.next("");
    } else if (keyword == "POINT_DATA" || keyword == "CELL_DATA" || keyword == "FIELD") {
      break;
    } else {
      in.fail("expected POINTS, CELLS or CELL_TYPES, found '" + std::string(keyword.substr(0, 40)) +
              "'");
    }
  }
  if (!has_points) in.fail("the file has no POINTS section");
  if (!has_cells) in.fail("the file has no CELLS section");
  if (!has_types) in.fail("the file has no CELL_TYPES section");
  size_t cell_count = cells.offsets.size() - 1;
  if (types.size() != cell_count) {
    in.fail_at(types_line, "CELL_TYPES lists " + std::to_string(types.size()) + " types for " +
                               std::to_string(cell_count) + " cells");
  }
  size_t points = out.positions.size() / 3;
  std::vector<int64_t> tet;
  for (size_t c = 0; c < cell_count; ++c) {
    tet.assign(cells.connectivity.begin() + cells.offsets[c],
               cells.connectivity.begin() + cells.offsets[c + 1]);
    check_vtk_cell(path, cells.line, c, types[c], tet, points);
    if (types[c] != kVtkTetra) {
      ++report.skipped_elements;
      continue;
    }
    for (int64_t index : tet) out.tets.push_back(static_cast<uint32_t>(index));
  }
  return out;
}

}  // namespace tacta::mesh_detail
