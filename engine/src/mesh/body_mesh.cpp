// The mesh a scene body names: a primitive, a volume file, or a surface file that gets voxelised.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <string>

#include "mesh/volume_readers.hpp"
#include "mesh/tet_budget.hpp"
#include "tacta/embedded_surface.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {

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
  if (desc.max_tets < 0 || desc.max_tets > kMaxTetsLimit)
    throw InputError({source, 0, 0, ""}, "max_tets must be 0 (the default budget) or in [1, " +
                                             std::to_string(kMaxTetsLimit) + "]");
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
    if (desc.max_tets > 0)
      throw InputError({desc.path, 0, 0, ""},
                       "max_tets sizes a body made from a surface file; this is a volume mesh, "
                       "used as it is (remove max_tets)");
    VolumeMesh mesh = mesh_detail::read_volume_raw(desc.path, r);
    transform(mesh.positions, desc);
    finalize(mesh, &r);
    note_pieces(mesh, r);
    return mesh;
  }
  SurfaceMesh surface = load_placed_surface(desc.path, desc, r);
  const auto max_tets =
      static_cast<size_t>(desc.max_tets > 0 ? desc.max_tets : kDefaultMaxTets);
  if (desc.tetrahedralize) {
    VolumeMesh mesh = desc.tetrahedralize->max_volume > 0
                          ? tetrahedralize(surface, *desc.tetrahedralize, &r)
                          : mesh_detail::tetrahedralize_within_budget(
                                surface, *desc.tetrahedralize, max_tets, r);
    note_pieces(mesh, r);
    return mesh;
  }
  const double voxel = desc.voxel_size;
  if (!std::isfinite(voxel) || voxel < 0)
    throw InputError({desc.path, 0, 0, ""}, "voxel_size must be 0 (automatic) or positive");
  // Majority keeps the body's volume, hence its mass, within a few % of the enclosed volume
  // (Cover overestimates it by about half a cell over the whole surface: 2x for liver.obj at the
  // automatic cell size).
  VolumeMesh mesh = voxel > 0 ? voxelize(surface, voxel, &r, VoxelFill::Majority)
                              : mesh_detail::voxelize_within_budget(surface, max_tets, r);
  note_pieces(mesh, r);
  return mesh;
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
  // The budget and what it gave: the tets against max_tets, the voxel against the thin parts'.
  std::string budget;
  if (r.max_tets > 0 && r.voxel_size > 0)
    budget = fmt::format(" within max_tets {} (thin parts ask for {:.4g} m voxels)", r.max_tets,
                         r.thin_part_size);
  else if (r.max_tets > 0 && r.budget_max_volume > 0)
    budget = fmt::format(" within max_tets {} (remeshed at max_volume {:.4g} m^3)", r.max_tets,
                         r.budget_max_volume);
  else if (r.max_tets > 0)
    budget = fmt::format(" within max_tets {}", r.max_tets);
  if (r.voxel_size > 0) {
    text = fmt::format(
        "voxelised{}: voxel {:.4g} m, {} cells, {}, volume {:.4g} m^3 = {:.1f}% of the {:.4g} m^3 "
        "enclosed, {} piece(s) from {} surface shell(s)",
        budget, r.voxel_size, r.voxel_cells, text, r.mesh_volume,
        r.enclosed_volume > 0 ? 100 * r.mesh_volume / r.enclosed_volume : 0.0, r.enclosed_volume,
        r.piece_volumes.size(), r.shells);
  } else if (r.format == "gmsh-tetrahedralize") {
    const MeshQuality q = mesh_quality(mesh);
    text = fmt::format(
        "tetrahedralized by Gmsh{}: {}, smallest dihedral angle {:.2f} degrees, radius ratio min "
        "{:.3f} mean {:.3f}",
        budget, text, q.min_dihedral_deg, q.min_radius_ratio, q.mean_radius_ratio);
  } else if (!r.format.empty()) {
    text = r.format + ": " + text;
  }
  return text;
}

}  // namespace tacta
