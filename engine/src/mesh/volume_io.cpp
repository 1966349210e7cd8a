// Volume files: the format is read from the first bytes of the file, never from its extension
// (SOFA's Bunny.vtk is XML), then the matching reader runs and the mesh is finalized.
#include <cstring>
#include <fstream>
#include <string>
#include <string_view>

#include "mesh/volume_readers.hpp"
#include "mesh/text_reader.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {

MeshFormat detect_text_format(std::string_view head, bool surface_is_other) {
  if (head.size() >= 3 && static_cast<unsigned char>(head[0]) == 0xEF &&
      static_cast<unsigned char>(head[1]) == 0xBB && static_cast<unsigned char>(head[2]) == 0xBF) {
    head.remove_prefix(3);  // UTF-8 byte order mark
  }
  size_t start = head.find_first_not_of(" \t\r\n");
  if (start == std::string_view::npos) return MeshFormat::Other;
  head.remove_prefix(start);
  if (head.starts_with("$MeshFormat")) {
    std::string_view rest = head.substr(std::strlen("$MeshFormat"));
    size_t v = rest.find_first_not_of(" \t\r\n");
    if (v != std::string_view::npos && rest[v] == '4') return MeshFormat::GmshV4;
    return MeshFormat::GmshV2;
  }
  if (head.starts_with("$NOD")) return MeshFormat::GmshV1;
  // VTK PolyData is a surface (load_surface reads it): Other for the callers that choose between
  // the volume and the surface loaders. Its dataset type is in the header (legacy) or the tag.
  const std::string_view window = head.substr(0, 4096);
  if (head.starts_with("# vtk DataFile")) {
    const size_t dataset = window.find("DATASET");
    const size_t type =
        dataset == std::string_view::npos ? dataset : window.find_first_not_of(" \t", dataset + 7);
    if (surface_is_other && type != std::string_view::npos &&
        window.substr(type).starts_with("POLYDATA"))
      return MeshFormat::Other;
    return MeshFormat::VtkLegacy;
  }
  if (head.starts_with("<")) {
    const size_t tag = window.find("<VTKFile");
    if (tag == std::string_view::npos) return MeshFormat::Other;
    const std::string_view attributes = window.substr(tag, window.find('>', tag) - tag);
    if (surface_is_other && (attributes.find("\"PolyData\"") != std::string_view::npos ||
                             attributes.find("'PolyData'") != std::string_view::npos))
      return MeshFormat::Other;
    return MeshFormat::VtkXml;
  }
  return MeshFormat::Other;
}

}  // namespace

MeshFormat detect_mesh_format(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0, ""}, "cannot open the file");
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return detect_text_format(head, true);
}

const char* mesh_format_name(MeshFormat format) {
  switch (format) {
    case MeshFormat::GmshV1: return "gmsh-1";
    case MeshFormat::GmshV2: return "gmsh-2.2";
    case MeshFormat::GmshV4: return "gmsh-4.1";
    case MeshFormat::VtkLegacy: return "vtk-legacy";
    case MeshFormat::VtkXml: return "vtk-xml";
    case MeshFormat::Other: return "other";
  }
  return "other";
}

namespace mesh_detail {

namespace {
VolumeMesh read_by_format(const std::string& path, LoadReport& report) {
  std::string text = read_file_bytes(path);
  if (text.find_first_not_of(" \t\r\n") == std::string::npos)
    throw InputError({path, 0, 0, ""}, "the file is empty");
  switch (detect_text_format(text, false)) {  // PolyData: the VTK reader says it is a surface
    case MeshFormat::GmshV1:
    case MeshFormat::GmshV2:
    case MeshFormat::GmshV4: return read_gmsh(path, text, report);
    case MeshFormat::VtkLegacy: return read_vtk_legacy(path, text, report);
    case MeshFormat::VtkXml: return read_vtk_xml(path, text, report);
    case MeshFormat::Other: break;
  }
  throw InputError(
      {path, 1, 0, ""},
      "unknown volume mesh format: expected Gmsh .msh (v1 $NOD, v2.2 or v4.1 $MeshFormat), "
      "VTK legacy ('# vtk DataFile') or VTK XML (<VTKFile>)");
}
}  // namespace

VolumeMesh read_volume_raw(const std::string& path, LoadReport& report) {
  VolumeMesh mesh = read_by_format(path, report);
  if (report.skipped_elements > 0) {
    report.warnings.push_back(std::to_string(report.skipped_elements) +
                              " elements that are not tetrahedra were skipped");
  }
  if (mesh.tets.empty()) {
    throw InputError({path, 0, 0, ""}, "the file holds no tetrahedra (" +
                                           std::to_string(report.skipped_elements) +
                                           " other elements); a volume mesh needs tets");
  }
  return mesh;
}

}  // namespace mesh_detail

VolumeMesh load_volume(const std::string& path, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  VolumeMesh mesh = mesh_detail::read_volume_raw(path, r);
  finalize(mesh, &r);
  return mesh;
}

}  // namespace tacta
