// The mesh a scene body names: a primitive, a volume file, or a surface file that gets voxelised.
#include <cmath>
#include <string>

#include "mesh/readers.hpp"
#include "tacta/embedded_surface.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {

constexpr double kAutoVoxelsPerDiagonal = 20;  // voxel_size 0: bounding-box diagonal / 20

bool is_identity(const MeshSourceDesc& d) {
  return d.scale == Vec3{1, 1, 1} && d.translate == Vec3{0, 0, 0};
}

void check_transform(const MeshSourceDesc& d, const std::string& source) {
  for (size_t a = 0; a < 3; ++a) {
    if (!std::isfinite(d.scale[a]) || d.scale[a] == 0) throw InputError({source, 0, 0, ""}, "mesh scale must be finite and non-zero on every axis");
    if (!std::isfinite(d.translate[a])) throw InputError({source, 0, 0, ""}, "mesh translate must be finite");
  }
}

// x -> scale * x + translate, component-wise, on a flat array of points.
void transform(std::vector<double>& positions, const MeshSourceDesc& d) {
  for (size_t i = 0; i < positions.size(); ++i) positions[i] = d.scale[i % 3] * positions[i] + d.translate[i % 3];
}

double bounding_diagonal(const SurfaceMesh& s) {
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (size_t i = 0; i < s.positions.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], s.positions[i]);
    hi[i % 3] = std::max(hi[i % 3], s.positions[i]);
  }
  return std::hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
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
SurfaceMesh load_placed_surface(const std::string& path, const MeshSourceDesc& desc, LoadReport& r) {
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
    return mesh;
  }
  if (detect_mesh_format(desc.path) != MeshFormat::Other) {
    VolumeMesh mesh = mesh_detail::read_volume_raw(desc.path, r);
    transform(mesh.positions, desc);
    finalize(mesh, &r);
    return mesh;
  }
  SurfaceMesh surface = load_placed_surface(desc.path, desc, r);
  if (desc.tetrahedralize) return tetrahedralize(surface, *desc.tetrahedralize, &r);
  double voxel = desc.voxel_size;
  if (!std::isfinite(voxel) || voxel < 0) throw InputError({desc.path, 0, 0, ""}, "voxel_size must be 0 (automatic) or positive");
  if (voxel == 0) voxel = bounding_diagonal(surface) / kAutoVoxelsPerDiagonal;
  if (!(voxel > 0)) throw InputError({desc.path, 0, 0, ""}, "the surface is flat or a point: it encloses no volume");
  // Majority keeps the body's volume, hence its mass, within a few % of the enclosed volume
  // (Cover overestimates it by about half a cell over the whole surface: 2x for liver.obj at the
  // automatic cell size).
  return voxelize(surface, voxel, &r, VoxelFill::Majority);
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
    mesh.embedding = bind_surface_to_tets(load_placed_surface(desc.surface_path, desc, surface_report), mesh, &surface_report);
    for (const std::string& w : surface_report.warnings) r.warnings.push_back("surface " + desc.surface_path + ": " + w);
  }
  return mesh;
}

}  // namespace tacta
