// The volume-file readers behind load_volume. Each returns the raw mesh (node positions and the
// tets as the file gives them, not yet finalized) and fills report.format and skipped_elements.
#pragma once

#include <string>
#include <string_view>

#include "tacta/mesh.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta::mesh_detail {

VolumeMesh read_gmsh(const std::string& path, std::string_view text, LoadReport& report);
VolumeMesh read_vtk_legacy(const std::string& path, std::string_view text, LoadReport& report);
VolumeMesh read_vtk_xml(const std::string& path, const std::string& text, LoadReport& report);

// Any volume file, format found from its content; throws when it holds no tets. Not finalized.
VolumeMesh read_volume_raw(const std::string& path, LoadReport& report);

// VTK cell type 10 and Gmsh types 4 and 11 are tets; the rest are counted and skipped.
inline constexpr int kVtkTetra = 10;

}  // namespace tacta::mesh_detail
