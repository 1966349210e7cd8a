// `tacta mesh-info FILE [--json]`: what a mesh file holds, or why it cannot be read. The format
// comes from the file's content: Gmsh and VTK grids are read as tet meshes (counts, bounds, element
// quality, total volume), anything else (VTK PolyData included) as a surface (counts, bounds,
// closedness, enclosed volume). Exit 0 when it loads, 2 when the file is bad (the error names
// file and line).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <numeric>
#include <string>

#include "command.hpp"
#include "tacta/error.hpp"
#include "tacta/log.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace {

struct Summary {
  std::string kind;  // "volume" or "surface"
  size_t nodes = 0, tets = 0, triangles = 0, edges = 0;
  double volume = 0;  // m^3: sum of tet volumes, or the surface's enclosed volume
  tacta::MeshQuality quality;
  tacta::LoadReport report;
  std::string as_body;  // a surface: what a scene body made of it becomes (automatic voxels)
  tacta::LoadReport body_report;
  size_t body_nodes = 0, body_tets = 0;  // of that body; 0 when refused
};

Summary summarize(const std::string& path) {
  Summary s;
  if (tacta::detect_mesh_format(path) != tacta::MeshFormat::Other) {
    tacta::VolumeMesh mesh = tacta::load_volume(path, &s.report);
    s.kind = "volume";
    s.nodes = mesh.node_count();
    s.tets = mesh.tet_count();
    s.triangles = mesh.triangles.size() / 3;
    s.edges = mesh.edges.size() / 2;
    s.quality = tacta::mesh_quality(mesh);
    std::vector<double> unit_masses =
        tacta::lumped_masses(mesh, 1.0);  // at 1 kg/m^3 mass is volume
    s.volume = std::accumulate(unit_masses.begin(), unit_masses.end(), 0.0);
    return s;
  }
  tacta::SurfaceMesh surface = tacta::load_surface(path, &s.report);
  s.kind = "surface";
  s.nodes = surface.vertex_count();
  s.triangles = surface.triangle_count();
  s.volume = tacta::enclosed_volume(surface);
  tacta::VolumeMesh points_only;  // bounds come from the positions alone
  points_only.positions = surface.positions;
  s.quality = tacta::mesh_quality(points_only);
  // What `mesh: {file: ...}` makes of it in a scene: the automatic voxelisation, or why it fails.
  tacta::MeshSourceDesc as_body;
  as_body.path = path;
  try {
    const tacta::VolumeMesh body = tacta::load_body_mesh(as_body, &s.body_report);
    s.as_body = tacta::describe_body_mesh(body, s.body_report);
    s.body_nodes = body.node_count();
    s.body_tets = body.tet_count();
  } catch (const tacta::InputError& e) {
    s.as_body = std::string("refused: ") + e.what();
  }
  s.quality.min_edge = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t < surface.triangle_count(); ++t) {
    for (size_t k = 0; k < 3; ++k) {
      const double* a = &surface.positions[3 * size_t{surface.triangles[3 * t + k]}];
      const double* b = &surface.positions[3 * size_t{surface.triangles[3 * t + (k + 1) % 3]}];
      double length = std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                                (b[2] - a[2]) * (b[2] - a[2]));
      s.quality.min_edge = std::min(s.quality.min_edge, length);
      s.quality.max_edge = std::max(s.quality.max_edge, length);
    }
  }
  return s;
}

void print_text(const std::string& path, const Summary& s) {
  const tacta::MeshQuality& q = s.quality;
  std::cout << path << "\n  format: " << s.report.format << " (" << s.kind << ")\n";
  if (s.kind == "volume") {
    std::cout << "  nodes: " << s.nodes << "\n  tets: " << s.tets
              << "\n  boundary triangles: " << s.triangles << "\n  edges: " << s.edges
              << "\n  skipped non-tet elements: " << s.report.skipped_elements
              << "\n  inverted tets re-oriented: " << s.report.inverted_tets
              << "\n  unused nodes removed: " << s.report.removed_nodes
              << "\n  volume: " << s.volume << " m^3"
              << "\n  tet volume: min " << q.min_volume << ", max " << q.max_volume << " m^3"
              << "\n  edge length: min " << q.min_edge << ", max " << q.max_edge << " m"
              << "\n  worst aspect ratio: " << q.worst_aspect_ratio << " (1 = regular tet)"
              << "\n  dihedral angle: min " << q.min_dihedral_deg << ", max " << q.max_dihedral_deg
              << " degrees"
              << "\n  radius ratio (3 r_in / r_circ, 1 regular): min " << q.min_radius_ratio
              << ", mean " << q.mean_radius_ratio << "\n";
  } else {
    std::cout << "  vertices: " << s.nodes << "\n  triangles: " << s.triangles
              << "\n  welded vertices: " << s.report.welded_vertices
              << "\n  degenerate triangles dropped: " << s.report.degenerate_triangles
              << "\n  closed: " << (s.report.closed() ? "yes" : "no") << " ("
              << s.report.boundary_edges << " open edges, " << s.report.nonmanifold_edges
              << " non-manifold edges)"
              << "\n  enclosed volume: " << s.volume << " m^3"
              << "\n  edge length: min " << q.min_edge << ", max " << q.max_edge << " m"
              << "\n  as a scene body: " << s.as_body << "\n";
    if (s.body_report.max_tets > 0) {
      std::cout << "  tet budget: max_tets " << s.body_report.max_tets << " (default "
                << tacta::kDefaultMaxTets << ") gave " << s.body_tets << " tets, " << s.body_nodes
                << " nodes, voxel " << s.body_report.voxel_size << " m; the thin parts ask for "
                << s.body_report.thin_part_size << " m\n";
    }
    for (const std::string& w : s.body_report.warnings)
      std::cout << "  as a scene body, warning: " << w << "\n";
  }
  std::cout << "  bounds: [" << q.bounds_min[0] << ", " << q.bounds_min[1] << ", "
            << q.bounds_min[2] << "] .. [" << q.bounds_max[0] << ", " << q.bounds_max[1] << ", "
            << q.bounds_max[2] << "] m\n";
  for (const std::string& w : s.report.warnings) std::cout << "  warning: " << w << "\n";
}

using Json = nlohmann::ordered_json;

// NaN and infinities are null; bytes that are not UTF-8 (a file name) become U+FFFD.
void print(const Json& json) {
  std::cout << json.dump(2, ' ', false, Json::error_handler_t::replace) << "\n";
}

void print_json(const std::string& path, const Summary& s) {
  const tacta::MeshQuality& q = s.quality;
  Json json = {{"file", path}, {"format", s.report.format}, {"kind", s.kind}};
  json[s.kind == "volume" ? "nodes" : "vertices"] = static_cast<uint64_t>(s.nodes);
  json["triangles"] = static_cast<uint64_t>(s.triangles);
  if (s.kind == "volume") {
    json["tets"] = static_cast<uint64_t>(s.tets);
    json["edges"] = static_cast<uint64_t>(s.edges);
    json["skipped_elements"] = static_cast<uint64_t>(s.report.skipped_elements);
    json["inverted_tets"] = static_cast<uint64_t>(s.report.inverted_tets);
    json["removed_nodes"] = static_cast<uint64_t>(s.report.removed_nodes);
    json["volume_m3"] = s.volume;
    json["quality"] = {{"min_tet_volume_m3", q.min_volume},
                       {"max_tet_volume_m3", q.max_volume},
                       {"min_edge_m", q.min_edge},
                       {"max_edge_m", q.max_edge},
                       {"worst_aspect_ratio", q.worst_aspect_ratio},
                       {"min_dihedral_deg", q.min_dihedral_deg},
                       {"max_dihedral_deg", q.max_dihedral_deg},
                       {"min_radius_ratio", q.min_radius_ratio},
                       {"mean_radius_ratio", q.mean_radius_ratio}};
  } else {
    json["welded_vertices"] = static_cast<uint64_t>(s.report.welded_vertices);
    json["degenerate_triangles"] = static_cast<uint64_t>(s.report.degenerate_triangles);
    json["closed"] = s.report.closed();
    json["open_edges"] = static_cast<uint64_t>(s.report.boundary_edges);
    json["nonmanifold_edges"] = static_cast<uint64_t>(s.report.nonmanifold_edges);
    json["enclosed_volume_m3"] = s.volume;
    json["min_edge_m"] = q.min_edge;
    json["max_edge_m"] = q.max_edge;
    json["as_body"] = {{"summary", s.as_body},
                       {"voxel_size_m", s.body_report.voxel_size},
                       {"voxel_cells", static_cast<uint64_t>(s.body_report.voxel_cells)},
                       {"max_tets", static_cast<uint64_t>(s.body_report.max_tets)},
                       {"thin_part_size_m", s.body_report.thin_part_size},
                       {"tets", static_cast<uint64_t>(s.body_tets)},
                       {"nodes", static_cast<uint64_t>(s.body_nodes)},
                       {"volume_m3", s.body_report.mesh_volume},
                       {"piece_volumes_m3", s.body_report.piece_volumes},
                       {"warnings", s.body_report.warnings}};
  }
  json["bounds_min_m"] = Json::array({q.bounds_min[0], q.bounds_min[1], q.bounds_min[2]});
  json["bounds_max_m"] = Json::array({q.bounds_max[0], q.bounds_max[1], q.bounds_max[2]});
  json["warnings"] = s.report.warnings;
  print(json);
}

void add_mesh_info_command(CLI::App& app, int& exit_code) {
  struct Options {
    std::string file;
    bool json = false;
  };
  auto options = std::make_shared<Options>();
  CLI::App* cmd = app.add_subcommand(
      "mesh-info",
      "Load a mesh (Gmsh .msh, VTK .vtk/.vtu tets; OBJ, STL, PLY, OFF, VTK PolyData .vtk/.vtp, "
      "glTF surfaces) and print its "
      "format, counts, bounds and quality, or the error that stops it loading");
  cmd->add_option("FILE", options->file, "The mesh file; its format is read from its content")
      ->required();
  cmd->add_flag("--json", options->json, "Print the same as JSON ({\"error\": ...} on failure)");
  cmd->callback([options, &exit_code] {
    Summary summary;
    try {
      summary = summarize(options->file);
    } catch (const tacta::InputError& e) {
      tacta::log_error(std::string("tacta mesh-info: ") + e.what());
      if (options->json) {
        print(Json{{"file", options->file}, {"error", e.what()}});
      }
      exit_code = tacta::cli::kExitBadInput;
      return;
    }
    if (options->json) {
      print_json(options->file, summary);
    } else {
      print_text(options->file, summary);
    }
    exit_code = tacta::cli::kExitOk;
  });
}

const bool registered = tacta::cli::register_command(&add_mesh_info_command);

}  // namespace
