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
#include <numeric>
#include <string>

#include "command.hpp"
#include "tacta/error.hpp"
#include "tacta/json.hpp"
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

void print_json(const std::string& path, const Summary& s) {
  const tacta::MeshQuality& q = s.quality;
  tacta::JsonWriter json(std::cout);
  json.begin_object();
  json.field("file", path).field("format", s.report.format).field("kind", s.kind);
  json.field(s.kind == "volume" ? "nodes" : "vertices", static_cast<uint64_t>(s.nodes));
  json.field("triangles", static_cast<uint64_t>(s.triangles));
  if (s.kind == "volume") {
    json.field("tets", static_cast<uint64_t>(s.tets))
        .field("edges", static_cast<uint64_t>(s.edges));
    json.field("skipped_elements", static_cast<uint64_t>(s.report.skipped_elements));
    json.field("inverted_tets", static_cast<uint64_t>(s.report.inverted_tets));
    json.field("removed_nodes", static_cast<uint64_t>(s.report.removed_nodes));
    json.field("volume_m3", s.volume);
    json.key("quality").begin_object();
    json.field("min_tet_volume_m3", q.min_volume).field("max_tet_volume_m3", q.max_volume);
    json.field("min_edge_m", q.min_edge).field("max_edge_m", q.max_edge);
    json.field("worst_aspect_ratio", q.worst_aspect_ratio);
    json.field("min_dihedral_deg", q.min_dihedral_deg)
        .field("max_dihedral_deg", q.max_dihedral_deg);
    json.field("min_radius_ratio", q.min_radius_ratio)
        .field("mean_radius_ratio", q.mean_radius_ratio);
    json.end_object();
  } else {
    json.field("welded_vertices", static_cast<uint64_t>(s.report.welded_vertices));
    json.field("degenerate_triangles", static_cast<uint64_t>(s.report.degenerate_triangles));
    json.field("closed", s.report.closed());
    json.field("open_edges", static_cast<uint64_t>(s.report.boundary_edges));
    json.field("nonmanifold_edges", static_cast<uint64_t>(s.report.nonmanifold_edges));
    json.field("enclosed_volume_m3", s.volume);
    json.field("min_edge_m", q.min_edge).field("max_edge_m", q.max_edge);
    json.key("as_body").begin_object().field("summary", s.as_body);
    json.field("voxel_size_m", s.body_report.voxel_size)
        .field("voxel_cells", static_cast<uint64_t>(s.body_report.voxel_cells));
    json.field("max_tets", static_cast<uint64_t>(s.body_report.max_tets))
        .field("thin_part_size_m", s.body_report.thin_part_size);
    json.field("tets", static_cast<uint64_t>(s.body_tets))
        .field("nodes", static_cast<uint64_t>(s.body_nodes));
    json.field("volume_m3", s.body_report.mesh_volume);
    json.key("piece_volumes_m3").begin_array();
    for (double v : s.body_report.piece_volumes) json.value(v);
    json.end_array();
    json.key("warnings").begin_array();
    for (const std::string& w : s.body_report.warnings) json.value(w);
    json.end_array().end_object();
  }
  json.key("bounds_min_m")
      .begin_array()
      .value(q.bounds_min[0])
      .value(q.bounds_min[1])
      .value(q.bounds_min[2])
      .end_array();
  json.key("bounds_max_m")
      .begin_array()
      .value(q.bounds_max[0])
      .value(q.bounds_max[1])
      .value(q.bounds_max[2])
      .end_array();
  json.key("warnings").begin_array();
  for (const std::string& w : s.report.warnings) json.value(w);
  json.end_array();
  json.end_object();
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
      std::cerr << "tacta mesh-info: " << e.what() << "\n";
      if (options->json) {
        tacta::JsonWriter json(std::cout);
        json.begin_object()
            .field("file", options->file)
            .field("error", std::string(e.what()))
            .end_object();
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
