#include "mesh/mesh_file_check.hpp"

#include <filesystem>
#include <unistd.h>

namespace tacta {

void require_mesh_file(const std::string& path, const SourceLocation& where) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (status.type() == std::filesystem::file_type::not_found)
    throw InputError(
        where, "no such file: " + path + " (a relative path is read from the scene's folder)");
  if (status.type() == std::filesystem::file_type::directory)
    throw InputError(where,
                     path +
                         " is a directory; expected a mesh file (.msh, .vtk, .vtu, .vtp, .obj, "
                         ".stl, .ply, .off, .gltf, ...)");
  if (ec || status.type() != std::filesystem::file_type::regular)
    throw InputError(where, path + " is not a regular file; expected a mesh file");
  if (access(path.c_str(), R_OK) != 0)
    throw InputError(where, "cannot read " + path + " (permission denied)");
}

}  // namespace tacta
