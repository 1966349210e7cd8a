// Checks shared by the VTK readers: a cell's point count must fit its type, and its point indices
// must name existing points. Cell type numbers from vtkCellType.h (VTK_TETRA = 10, ...).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tacta/error.hpp"

namespace tacta::mesh_detail {

// Points a cell of this type has; 0 when any count is allowed (poly-vertex, polygon, ...), -1 when
// the type is not a VTK cell type.
inline int vtk_points_per_cell(int64_t type) {
  switch (type) {
    case 1: return 1;  // vertex
    case 3: return 2;  // line
    case 5: return 3;  // triangle
    case 8:
    case 9:
    case 10: return 4;  // pixel, quad, tetra
    case 11:
    case 12: return 8;   // voxel, hexahedron
    case 13: return 6;   // wedge
    case 14: return 5;   // pyramid
    case 21: return 3;   // quadratic edge
    case 22: return 6;   // quadratic triangle
    case 23: return 8;   // quadratic quad
    case 24: return 10;  // quadratic tetra
    case 25: return 20;  // quadratic hexahedron
    case 2:
    case 4:
    case 6:
    case 7:
    case 42: return 0;  // poly-vertex, poly-line, strip, polygon, polyhedron
    default: return -1;
  }
}

inline void check_vtk_cell(const std::string& path, int line, size_t cell, int64_t type,
                           const std::vector<int64_t>& indices, size_t point_count) {
  int expected = vtk_points_per_cell(type);
  std::string name = "cell " + std::to_string(cell);
  if (expected < 0)
    throw InputError({path, line, 0, ""},
                     name + " has unknown VTK cell type " + std::to_string(type));
  if (expected > 0 && indices.size() != static_cast<size_t>(expected)) {
    throw InputError({path, line, 0, ""}, name + " of type " + std::to_string(type) +
                                              " must have " + std::to_string(expected) +
                                              " points, it has " + std::to_string(indices.size()));
  }
  for (int64_t index : indices) {
    if (index < 0 || static_cast<uint64_t>(index) >= point_count) {
      throw InputError({path, line, 0, ""}, name + " refers to point " + std::to_string(index) +
                                                ", outside [0, " + std::to_string(point_count) +
                                                ")");
    }
  }
}

}  // namespace tacta::mesh_detail
