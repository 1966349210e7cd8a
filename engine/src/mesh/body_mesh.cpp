// The mesh a scene body names: a primitive, a volume file, or a surface file that gets voxelised.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <string>

#include "mesh/readers.hpp"
#include "tacta/embedded_surface.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {

constexpr double kAutoVoxelsPerDiagonal = 20;  // voxel_size 0: at most bounding-box diagonal / 20
constexpr double kAutoMaxBoxCells =
    1e6;  // voxel_size 0: the grid's box stays under this many cells

bool is_identity(const MeshSourceDesc& d) {
  return d.scale == Vec3{1, 1, 1} && d.translate == Vec3{0, 0, 0};
}

void check_transform(const MeshSourceDesc& d, const std::string& source) {
  for (size_t a = 0; a < 3; ++a) {
    if (!std::isfinite(d.scale[a]) || d.scale[a] == 0)
      throw InputError({source, 0, 0, ""}, "mesh scale must be finite and non-zero on every axis");
    if (!std::isfinite(d.translate[a]))
      throw InputError({source, 0, 0, ""}, "mesh translate must be finite");
  }
}

// x -> scale * x + translate, component-wise, on a flat array of points.
void transform(std::vector<double>& positions, const MeshSourceDesc& d) {
  for (size_t i = 0; i < positions.size(); ++i)
    positions[i] = d.scale[i % 3] * positions[i] + d.translate[i % 3];
}

double surface_area(const SurfaceMesh& s) {
  double area = 0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const double* a = &s.positions[3 * size_t{s.triangles[3 * t]}];
    const double* b = &s.positions[3 * size_t{s.triangles[3 * t + 1]}];
    const double* c = &s.positions[3 * size_t{s.triangles[3 * t + 2]}];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]},
                 v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    area += 0.5 * std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2],
                             u[0] * v[1] - u[1] * v[0]);
  }
  return area;
}

// A tet mesh in more than one piece: each piece with no fixed node falls on its own.
void note_pieces(const VolumeMesh& mesh, LoadReport& r) {
  r.piece_volumes = piece_volumes(mesh);
  if (r.piece_volumes.size() < 2) return;
  std::string sizes;
  for (size_t i = 0; i < r.piece_volumes.size() && i < 8; ++i)
    sizes += fmt::format("{}{:.3g}", i ? ", " : "", r.piece_volumes[i]);
  r.warnings.push_back(fmt::format(
      "the mesh has {} separate pieces ({} m^3): a piece with no fixed node falls freely "
      "under gravity",
      r.piece_volumes.size(), sizes));
}

// The surface's bounding-box edge lengths, m.
std::array<double, 3> extent(const SurfaceMesh& s) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < s.positions.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], s.positions[i]);
    hi[i % 3] = std::max(hi[i % 3], s.positions[i]);
  }
  return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
}

// Whether a grid of this cell size over the surface's box stays under the automatic budget.
bool within_budget(const SurfaceMesh& s, double cell) {
  const std::array<double, 3> e = extent(s);
  return (e[0] / cell + 2) * (e[1] / cell + 2) * (e[2] / cell + 2) <= kAutoMaxBoxCells;
}

// The automatic voxel size: the bounding-box diagonal / 20, or finer for a thin body: volume /
// area is half a slab's thickness and a quarter of a rod's diameter, so a cell that size puts
// about 2 cells across a slab and 4 across a rod. The grid's box is kept under a million cells.
double automatic_voxel_size(const SurfaceMesh& s, LoadReport& r) {
  const std::array<double, 3> e = extent(s);
  double h = std::hypot(e[0], e[1], e[2]) / kAutoVoxelsPerDiagonal;
  const double area = surface_area(s), volume = std::abs(enclosed_volume(s));
  if (area > 0 && volume > 0) h = std::min(h, volume / area);
  if (h > 0 && !within_budget(s, h)) {
    const double thin = h;
    while (!within_budget(s, h)) h *= 1.1;
    r.warnings.push_back(fmt::format(
        "the body's thin parts ask for {:.3g} m voxels; {:.3g} m was used to keep the grid "
        "under a million cells (give voxel_size, or tetrahedralize, to choose)",
        thin, h));
  }
  return h;
}

VolumeMesh primitive(const MeshSourceDesc& d) {
  switch (d.kind) {
    case MeshSourceDesc::Kind::BoxGrid: return make_box_grid(d.size, d.cells, d.origin);
    case MeshSourceDesc::Kind::BeamGrid: return make_beam_grid(d.size, d.cells, d.origin);
    case MeshSourceDesc::Kind::QuadGrid: return make_quad_grid(d.size, d.cells, d.origin);
    case MeshSourceDesc::Kind::Sphere: return make_sphere(d.radius, d.origin, d.subdivisions);
    case MeshSourceDesc::Kind::File: break;
  }
  throw InputError({"", 0, 0, ""}, "unknown mesh primitive");
}

// A surface file as the scene places it: scaled, translated, outward even under a mirroring scale.
SurfaceMesh load_placed_surface(const std::string& path, const MeshSourceDesc& desc,
                                LoadReport& r) {
  SurfaceMesh surface = load_surface(path, &r);
  transform(surface.positions, desc);
  if (desc.scale[0] * desc.scale[1] * desc.scale[2] < 0) {
    for (size_t t = 0; t < surface.triangle_count(); ++t) {
      std::swap(surface.triangles[3 * t + 1], surface.triangles[3 * t + 2]);
      if (surface.corner_uvs.empty()) continue;
      std::swap(surface.corner_uvs[6 * t + 2], surface.corner_uvs[6 * t + 4]);
      std::swap(surface.corner_uvs[6 * t + 3], surface.corner_uvs[6 * t + 5]);
    }
  }
  return surface;
}

VolumeMesh load_tets(const MeshSourceDesc& desc, LoadReport& r) {
  const std::string source = desc.kind == MeshSourceDesc::Kind::File ? desc.path : "primitive";
  check_transform(desc, source);
  if (desc.kind != MeshSourceDesc::Kind::File) {
    VolumeMesh mesh = primitive(desc);
    r.format = mesh.source;
    if (!is_identity(desc)) {
      transform(mesh.positions, desc);
      finalize(mesh, &r);  // a mirroring scale turns every tet inside out: re-orient
    }
    note_pieces(mesh, r);
    return mesh;
  }
  if (detect_mesh_format(desc.path) != MeshFormat::Other) {
    VolumeMesh mesh = mesh_detail::read_volume_raw(desc.path, r);
    transform(mesh.positions, desc);
    finalize(mesh, &r);
    note_pieces(mesh, r);
    return mesh;
  }
  SurfaceMesh surface = load_placed_surface(desc.path, desc, r);
  if (desc.tetrahedralize) {
    VolumeMesh mesh = tetrahedralize(surface, *desc.tetrahedralize, &r);
    note_pieces(mesh, r);
    return mesh;
  }
  double voxel = desc.voxel_size;
  if (!std::isfinite(voxel) || voxel < 0)
    throw InputError({desc.path, 0, 0, ""}, "voxel_size must be 0 (automatic) or positive");
  const bool automatic = voxel == 0;
  if (automatic) voxel = automatic_voxel_size(surface, r);
  if (!(voxel > 0))
    throw InputError({desc.path, 0, 0, ""},
                     "the surface is flat or a point: it encloses no volume");
  // Majority keeps the body's volume, hence its mass, within a few % of the enclosed volume
  // (Cover overestimates it by about half a cell over the whole surface: 2x for liver.obj at the
  // automatic cell size).
  if (!automatic) {
    VolumeMesh mesh = voxelize(surface, voxel, &r, VoxelFill::Majority);
    note_pieces(mesh, r);
    return mesh;
  }
  // Automatic: where the inside cells split a shell apart, a finer grid (up to 3 times 1.5x finer,
  // within the cell budget) is tried before the crossed cells are kept to join the pieces.
  const LoadReport before = r;
  for (int refinement = 0;; ++refinement) {
    LoadReport attempt = before;
    VolumeMesh mesh = voxelize(surface, voxel, &attempt, VoxelFill::Majority);
    const double finer = voxel / 1.5;
    if (attempt.split_pieces == 0 || refinement == 3 || !within_budget(surface, finer)) {
      r = attempt;
      note_pieces(mesh, r);
      if (refinement > 0) {
        r.warnings.push_back(fmt::format(
            "the automatic voxel size was made {} times 1.5x finer to keep each surface shell "
            "in one piece",
            refinement));
      }
      return mesh;
    }
    voxel = finer;
  }
}

}  // namespace

VolumeMesh load_body_mesh(const MeshSourceDesc& desc, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  VolumeMesh mesh = load_tets(desc, r);
  if (desc.surface_tet_boundary) {
    mesh.embedding.reset();
  } else if (!desc.surface_path.empty()) {
    LoadReport surface_report;
    mesh.embedding = bind_surface_to_tets(
        load_placed_surface(desc.surface_path, desc, surface_report), mesh, &surface_report);
    for (const std::string& w : surface_report.warnings)
      r.warnings.push_back("surface " + desc.surface_path + ": " + w);
  }
  return mesh;
}

std::string describe_body_mesh(const VolumeMesh& mesh, const LoadReport& r) {
  std::string text =
      mesh.dimension == 2
          ? fmt::format("{} nodes, {} quads", mesh.node_count(), mesh.quads.size() / 4)
          : fmt::format("{} nodes, {} tets", mesh.node_count(), mesh.tet_count());
  if (r.voxel_size == 0 && !r.piece_volumes.empty())
    text += fmt::format(", {} piece(s)", r.piece_volumes.size());
  if (r.voxel_size > 0) {
    text = fmt::format(
        "voxelised: voxel {:.4g} m, {} cells, {}, volume {:.4g} m^3 = {:.1f}% of the {:.4g} m^3 "
        "enclosed, "
        "{} piece(s) from {} surface shell(s)",
        r.voxel_size, r.voxel_cells, text, r.mesh_volume,
        r.enclosed_volume > 0 ? 100 * r.mesh_volume / r.enclosed_volume : 0.0, r.enclosed_volume,
        r.piece_volumes.size(), r.shells);
  } else if (r.format == "gmsh-tetrahedralize") {
    const MeshQuality q = mesh_quality(mesh);
    text = fmt::format(
        "tetrahedralized by Gmsh: {}, smallest dihedral angle {:.2f} degrees, radius ratio min "
        "{:.3f} "
        "mean {:.3f}",
        text, q.min_dihedral_deg, q.min_radius_ratio, q.mean_radius_ratio);
  } else if (!r.format.empty()) {
    text = r.format + ": " + text;
  }
  return text;
}

}  // namespace tacta
