// A closed surface filled with conforming tetrahedra by Gmsh (GPL-2.0-or-later, Debian's
// libgmsh-dev): the surface triangles are kept as they are (the tets' boundary is exactly the
// user's surface) and the inside is meshed by Gmsh's 3D Delaunay, then optimised by Gmsh.
// The input is checked here first, so that Gmsh only ever sees a closed, outward, manifold shell.
#include <cmath>
#include <fmt/format.h>
#include <gmsh.h>
#include <numbers>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "mesh/isolated_call.hpp"
#include "tacta/mesh_build.hpp"

namespace tacta {

namespace {

// Every Gmsh call runs in a child process (call_isolated): Gmsh keeps state that outlives
// gmsh::finalize and gmsh::clear (the same surface meshed a second time in one process gave other
// tets), and a child that crashes on a bad surface is an error here, not a crash.
constexpr double kMesherTimeout = 600;  // s: far past any surface a haptic body can use

class GmshSession {
 public:
  GmshSession() {
    gmsh::initialize(0, nullptr, false);  // no user config files: the same result on every machine
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.Verbosity", 1);
    gmsh::option::setNumber("General.NumThreads", 1);  // one thread: the same mesh on every run
    gmsh::model::add("tacta");
  }
  ~GmshSession() { gmsh::finalize(); }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
};

std::string gmsh_error(const std::exception* e) {
  std::string last;
  gmsh::logger::getLastError(last);
  if (!last.empty()) return last;
  return e ? e->what() : "unknown Gmsh failure";
}

const std::string kGmshFailed =
    "Gmsh could not tetrahedralize the surface (are triangles crossing or touching? repair it in a "
    "mesh "
    "editor, or fill it with voxel_size instead): ";

// Gmsh numbers nodes from 1: tags 1..n for the nodes, and each element's node tags.
std::vector<std::size_t> gmsh_node_tags(size_t nodes) {
  std::vector<std::size_t> tags(nodes);
  for (size_t i = 0; i < nodes; ++i) tags[i] = i + 1;
  return tags;
}
std::vector<std::size_t> gmsh_element_nodes(const std::vector<uint32_t>& indices) {
  std::vector<std::size_t> tags(indices.size());
  for (size_t i = 0; i < indices.size(); ++i) tags[i] = std::size_t{indices[i]} + 1;
  return tags;
}

// Edge of the regular tet of volume v: v = a^3 / (6 sqrt 2).
double regular_edge(double volume) { return std::cbrt(6.0 * std::numbers::sqrt2 * volume); }

void check_surface(SurfaceMesh& s, LoadReport& r) {
  const std::string& source = s.source;
  if (s.triangle_count() < 4)
    throw InputError({source, 0, 0, ""},
                     "tetrahedralize needs a closed surface; this one has fewer than 4 triangles");
  check_closed(s, r);
  if (!r.closed()) {
    throw InputError(
        {source, 0, 0, ""},
        fmt::format(
            "tetrahedralize needs a closed, manifold surface; this one has {} open edges and {} "
            "non-manifold edges (close the holes in a mesh editor, or use voxel_size, which "
            "fills an open surface as a best guess)",
            r.boundary_edges, r.nonmanifold_edges));
  }
  const double volume = enclosed_volume(s);
  if (!(std::abs(volume) > 0) || !std::isfinite(volume))
    throw InputError({source, 0, 0, ""}, "the surface encloses no volume");
  if (volume < 0) {  // inward triangles: Gmsh wants them outward
    for (size_t t = 0; t < s.triangle_count(); ++t)
      std::swap(s.triangles[3 * t + 1], s.triangles[3 * t + 2]);
    r.warnings.push_back("the surface's triangles faced inward; they were flipped");
  }
}

void check_options(const TetrahedralizeDesc& o, const std::string& source) {
  if (!(o.max_volume >= 0) || !std::isfinite(o.max_volume))
    throw InputError({source, 0, 0, ""},
                     "tetrahedralize.max_volume must be 0 (automatic) or a positive volume in m^3");
  if (!(o.min_dihedral_deg >= 0 && o.min_dihedral_deg < 70))
    throw InputError(
        {source, 0, 0, ""},
        "tetrahedralize.min_dihedral must be in [0, 70) degrees (the regular tet has 70.5)");
  if (!(o.min_radius_ratio >= 0 && o.min_radius_ratio < 1))
    throw InputError({source, 0, 0, ""}, "tetrahedralize.min_radius_ratio must be in [0, 1)");
}

// The tets Gmsh holds now, as raw positions and 0-based tets (Gmsh's node tags renumbered).
VolumeMesh gmsh_tets(const std::string& source) {
  std::vector<std::size_t> node_tags, element_tags, tet_nodes;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false);
  gmsh::model::mesh::getElementsByType(4, element_tags, tet_nodes);  // 4: 4-node tetrahedra
  VolumeMesh mesh;
  mesh.source = source + " (tetrahedralized)";
  mesh.positions = coords;
  std::unordered_map<std::size_t, uint32_t> index;
  for (size_t i = 0; i < node_tags.size(); ++i) index[node_tags[i]] = static_cast<uint32_t>(i);
  mesh.tets.reserve(tet_nodes.size());
  for (std::size_t tag : tet_nodes) mesh.tets.push_back(index.at(tag));
  if (mesh.tets.empty()) throw std::runtime_error("Gmsh made no tetrahedra of this surface");
  return mesh;
}

bool reaches(const VolumeMesh& raw, const TetrahedralizeDesc& o) {
  VolumeMesh mesh = raw;
  finalize(mesh);
  const MeshQuality q = mesh_quality(mesh);
  return q.min_dihedral_deg >= o.min_dihedral_deg && q.min_radius_ratio >= o.min_radius_ratio;
}

// In the child: the surface into Gmsh, tets out, as bytes (positions then tets).
std::string mesh_in_gmsh(const SurfaceMesh& s, const TetrahedralizeDesc& options) {
  GmshSession session;
  VolumeMesh mesh;
  try {
    const int surface = gmsh::model::addDiscreteEntity(2);
    gmsh::model::mesh::addNodes(2, surface, gmsh_node_tags(s.vertex_count()), s.positions);
    gmsh::model::mesh::addElementsByType(surface, 2, {},
                                         gmsh_element_nodes(s.triangles));  // 2: 3-node triangles
    std::vector<int> shell_surfaces{surface};
    if (options.max_volume > 0) {
      // A size inside asks for a new surface mesh too: the surface is split into patches at 40
      // degree creases, each reparametrised and remeshed at that size (Gmsh's STL remeshing).
      gmsh::model::mesh::classifySurfaces(40 * std::numbers::pi / 180, true, true,
                                          std::numbers::pi);
      gmsh::model::mesh::createGeometry();
      gmsh::vectorpair patches;
      gmsh::model::getEntities(patches, 2);
      shell_surfaces.clear();
      for (const auto& [dim, tag] : patches) shell_surfaces.push_back(tag);
      gmsh::option::setNumber("Mesh.MeshSizeMax", regular_edge(options.max_volume));
    }
    const int shell = gmsh::model::geo::addSurfaceLoop(shell_surfaces);
    gmsh::model::geo::addVolume({shell});
    gmsh::model::geo::synchronize();
    // Delaunay: keeps the boundary triangles and gives the same tets every run (HXT, with fewer
    // slivers, gave other tets from one run to the next even on one thread).
    gmsh::option::setNumber("Mesh.Algorithm3D", 1);
    gmsh::option::setNumber("Mesh.Optimize", options.optimize ? 1 : 0);
    gmsh::model::mesh::generate(3);
    mesh = gmsh_tets(s.source);
    // Asked-for quality not reached yet: more passes of Gmsh's optimiser, then of node relocation
    // (Debian's Gmsh is built without Netgen).
    for (int pass = 0; pass < 3 && options.optimize && !reaches(mesh, options); ++pass) {
      gmsh::model::mesh::optimize("");
      gmsh::model::mesh::optimize("Relocate3D");
      mesh = gmsh_tets(s.source);
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(kGmshFailed + gmsh_error(&e));
  } catch (...) {
    throw std::runtime_error(kGmshFailed + gmsh_error(nullptr));
  }
  std::string bytes;
  mesh_detail::append_array(bytes, mesh.positions);
  mesh_detail::append_array(bytes, mesh.tets);
  return bytes;
}

}  // namespace

VolumeMesh tetrahedralize(const SurfaceMesh& closed, const TetrahedralizeDesc& options,
                          LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  SurfaceMesh s = closed;
  check_options(options, s.source);
  check_surface(s, r);
  const std::string bytes = mesh_detail::call_isolated([&] { return mesh_in_gmsh(s, options); },
                                                       s.source, kMesherTimeout);
  VolumeMesh mesh;
  mesh.source = s.source + " (tetrahedralized)";
  size_t at = 0;
  mesh.positions = mesh_detail::take_array<double>(bytes, at);
  mesh.tets = mesh_detail::take_array<uint32_t>(bytes, at);
  if (mesh.tets.empty() || at != bytes.size())
    throw InputError({s.source, 0, 0, ""}, "the mesher's answer was cut short");
  finalize(mesh, &r);
  const MeshQuality q = mesh_quality(mesh);
  if (q.min_dihedral_deg < options.min_dihedral_deg ||
      q.min_radius_ratio < options.min_radius_ratio) {
    throw InputError(
        {s.source, 0, 0, ""},
        fmt::format(
            "tetrahedralize reached a smallest dihedral angle of {:.2f} degrees and a smallest "
            "radius ratio of {:.3f}, short of the {:.2f} degrees and {:.3f} asked for (the surface "
            "triangles bound the quality: remesh the surface finer or ask for less)",
            q.min_dihedral_deg, q.min_radius_ratio, options.min_dihedral_deg,
            options.min_radius_ratio));
  }
  r.format = "gmsh-tetrahedralize";
  return mesh;
}

void write_gmsh(const VolumeMesh& mesh, const std::string& path) {
  mesh_detail::call_isolated(
      [&] {
        GmshSession session;
        try {
          const int volume = gmsh::model::addDiscreteEntity(3);
          gmsh::model::mesh::addNodes(3, volume, gmsh_node_tags(mesh.node_count()), mesh.positions);
          gmsh::model::mesh::addElementsByType(volume, 4, {},
                                               gmsh_element_nodes(mesh.tets));  // 4: 4-node tets
          gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
          gmsh::option::setNumber("Mesh.Binary", 0);
          gmsh::write(path);
        } catch (const std::exception& e) {
          throw std::runtime_error("cannot write the mesh: " + gmsh_error(&e));
        }
        return std::string();
      },
      path, kMesherTimeout);
}

}  // namespace tacta
