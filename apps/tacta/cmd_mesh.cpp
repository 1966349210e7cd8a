// `tacta mesh tetrahedralize IN OUT.msh`: a closed surface (OBJ, STL, PLY, OFF, VTK, glTF) filled with
// conforming quality tetrahedra by Gmsh, written as a Gmsh 4.1 .msh, with a quality report
// (counts, smallest and largest dihedral angle, radius ratio). Exit 2 on an open or bad surface.
#include <cstdio>
#include <memory>
#include <string>

#include "command.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace {

void print_quality(const tacta::VolumeMesh& mesh, const tacta::LoadReport& report) {
  const tacta::MeshQuality q = tacta::mesh_quality(mesh);
  std::printf("  nodes: %zu\n  tets: %zu\n  boundary triangles: %zu\n", mesh.node_count(),
              mesh.tet_count(), mesh.triangles.size() / 3);
  std::printf("  dihedral angle: min %.2f, max %.2f degrees\n", q.min_dihedral_deg,
              q.max_dihedral_deg);
  std::printf("  radius ratio (3 r_in / r_circ, 1 regular): min %.4f, mean %.3f\n",
              q.min_radius_ratio, q.mean_radius_ratio);
  std::printf("  tet volume: min %.4g, max %.4g m^3\n", q.min_volume, q.max_volume);
  for (const std::string& w : report.warnings) std::printf("  warning: %s\n", w.c_str());
}

void add_mesh_command(CLI::App& app, int& exit_code) {
  CLI::App* mesh = app.add_subcommand("mesh", "Mesh tools: tetrahedralize a closed surface");
  mesh->require_subcommand(1);
  struct Options {
    std::string in, out;
    tacta::TetrahedralizeDesc tet;
  };
  auto o = std::make_shared<Options>();
  CLI::App* tet = mesh->add_subcommand(
      "tetrahedralize",
      "Fill a closed surface with conforming quality tetrahedra (Gmsh) and write a .msh");
  tet->add_option("IN", o->in,
                  "A closed triangle surface (OBJ, STL, PLY, OFF, VTK PolyData .vtk/.vtp, glTF)")
      ->required();
  tet->add_option("OUT", o->out, "The tetrahedral mesh to write (Gmsh 4.1 .msh)")->required();
  tet->add_option("--max-volume", o->tet.max_volume,
                  "Largest tet, m^3 (0: sized from the surface triangles)")
      ->check(CLI::NonNegativeNumber);
  tet->add_option("--min-dihedral", o->tet.min_dihedral_deg,
                  "Smallest dihedral angle to reach, degrees (exit 2 if not)")
      ->check(CLI::Range(0.0, 60.0));
  tet->add_option("--min-radius-ratio", o->tet.min_radius_ratio,
                  "Smallest radius ratio to reach (exit 2 if not)")
      ->check(CLI::Range(0.0, 0.9));
  tet->add_flag("!--no-optimize", o->tet.optimize, "Skip Gmsh's optimiser");
  tet->callback([o, &exit_code] {
    exit_code = tacta::cli::run_guarded([&] {
      tacta::LoadReport report;
      tacta::SurfaceMesh surface = tacta::load_surface(o->in, &report);
      tacta::VolumeMesh volume = tacta::tetrahedralize(surface, o->tet, &report);
      tacta::write_gmsh(volume, o->out);
      std::printf("%s -> %s\n", o->in.c_str(), o->out.c_str());
      print_quality(volume, report);
      return tacta::cli::kExitOk;
    });
  });
}

const bool registered = tacta::cli::register_command(&add_mesh_command);

}  // namespace
