// Triangle surfaces: PLY, OBJ, OFF and VTK PolyData by our own readers, STL (checked first) and
// glTF through assimp.
// assimp's own vertex joining keeps vertices apart when their normals or texture coordinates
// differ (every STL corner, OBJ seams), so positions are welded again here, exactly, across all
// sub-meshes: a body's surface must be one connected mesh.
#include <algorithm>
#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/importerdesc.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <string>
#include <unordered_map>

#include "mesh/geometry.hpp"
#include "mesh/surface_readers.hpp"
#include "mesh/text_reader.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {

constexpr double kDegenerateArea =
    1e-12;  // |cross| below this times (longest edge)^2 is a flat triangle

struct PositionKey {
  uint64_t bits[3];
  bool operator==(const PositionKey& o) const {
    return std::memcmp(bits, o.bits, sizeof bits) == 0;
  }
};
struct PositionHash {
  size_t operator()(const PositionKey& k) const {
    uint64_t h = 1469598103934665603ull;  // FNV-1a over the three bit patterns
    for (uint64_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return static_cast<size_t>(h);
  }
};

class SurfaceBuilder {
 public:
  SurfaceBuilder(SurfaceMesh& out, LoadReport& report) : out_(out), report_(report) {}

  void add_mesh(const aiMesh& mesh, const aiMatrix4x4& transform) {
    std::vector<uint32_t> local(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      aiVector3D p = transform * mesh.mVertices[v];
      double xyz[3] = {static_cast<double>(p.x) + 0.0, static_cast<double>(p.y) + 0.0,
                       static_cast<double>(p.z) + 0.0};
      local[v] = add_vertex(xyz, [&] {
        return "vertex " + std::to_string(v) + " of mesh '" + mesh.mName.C_Str() + "'";
      });
    }
    const bool mirrored = transform.Determinant() < 0;  // a mirror flips the winding
    const aiVector3D* uv = mesh.HasTextureCoords(0) ? mesh.mTextureCoords[0] : nullptr;
    any_uv_ = any_uv_ || uv != nullptr;
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) {
        ++non_triangles_;  // points and lines that Triangulate leaves alone
        continue;
      }
      uint32_t t[3];
      double corner_uv[6] = {0, 0, 0, 0, 0, 0};  // a sub-mesh without coordinates gets zeros
      for (int k = 0; k < 3; ++k) {
        unsigned i = face.mIndices[k];
        if (i >= mesh.mNumVertices)
          throw InputError({out_.source, 0, 0, ""},
                           "a face refers to a vertex that does not exist");
        t[k] = local[i];
        if (uv != nullptr) corner_uv[2 * k] = uv[i].x, corner_uv[2 * k + 1] = uv[i].y;
      }
      if (mirrored) {
        std::swap(t[1], t[2]);
        std::swap(corner_uv[2], corner_uv[4]);
        std::swap(corner_uv[3], corner_uv[5]);
      }
      add_triangle(t, corner_uv);
    }
  }

  // Polygons (validated by the reader) as fans from their first vertex.
  void add_polygons(const mesh_detail::PolygonSoup& soup) {
    std::vector<uint32_t> local(soup.positions.size() / 3);
    for (size_t v = 0; v < local.size(); ++v) {
      local[v] = add_vertex(&soup.positions[3 * v], [&] { return "vertex " + std::to_string(v); });
    }
    report_.warnings.insert(report_.warnings.end(), soup.warnings.begin(), soup.warnings.end());
    const bool has_uv = !soup.corner_uvs.empty();
    any_uv_ = any_uv_ || has_uv;
    for (size_t f = 0; f + 1 < soup.face_starts.size(); ++f) {
      const uint32_t first = soup.face_starts[f];
      for (uint32_t k = first + 1; k + 1 < soup.face_starts[f + 1]; ++k) {
        const uint32_t corners[3] = {first, k, k + 1};
        uint32_t t[3];
        double corner_uv[6] = {0, 0, 0, 0, 0, 0};
        for (int c = 0; c < 3; ++c) {
          t[c] = local[soup.indices[corners[c]]];
          if (has_uv)
            corner_uv[2 * c] = soup.corner_uvs[2 * corners[c]],
                          corner_uv[2 * c + 1] = soup.corner_uvs[2 * corners[c] + 1];
        }
        add_triangle(t, corner_uv);
      }
    }
  }

  void finish() {
    if (!any_uv_) out_.corner_uvs.clear();
    report_.welded_vertices += welded_;
    if (report_.degenerate_triangles > 0) {
      report_.warnings.push_back(
          std::to_string(report_.degenerate_triangles) +
          " degenerate triangles (zero area or a repeated vertex) were dropped");
    }
    if (non_triangles_ > 0)
      report_.warnings.push_back(std::to_string(non_triangles_) + " points or lines were ignored");
  }

 private:
  template <class Describe>
  uint32_t add_vertex(const double xyz_in[3], Describe describe) {
    double xyz[3] = {xyz_in[0] + 0.0, xyz_in[1] + 0.0, xyz_in[2] + 0.0};  // -0 welds with +0
    if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) {
      throw InputError({out_.source, 0, 0, ""}, describe() + " has a NaN or infinite coordinate");
    }
    PositionKey key;
    std::memcpy(key.bits, xyz, sizeof key.bits);
    auto [it, inserted] = index_.emplace(key, static_cast<uint32_t>(out_.vertex_count()));
    if (inserted) {
      out_.positions.insert(out_.positions.end(), xyz, xyz + 3);
    } else {
      ++welded_;
    }
    return it->second;
  }

  void add_triangle(const uint32_t t[3], const double corner_uv[6]) {
    if (degenerate(t)) {
      ++report_.degenerate_triangles;
      return;
    }
    out_.triangles.insert(out_.triangles.end(), t, t + 3);
    out_.corner_uvs.insert(out_.corner_uvs.end(), corner_uv, corner_uv + 6);
  }

  bool degenerate(const uint32_t t[3]) const {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
    Vec3 a = mesh_detail::point(out_.positions, t[0]), b = mesh_detail::point(out_.positions, t[1]),
         c = mesh_detail::point(out_.positions, t[2]);
    double longest = std::max({distance(b, a), distance(c, b), distance(a, c)});
    return !(norm(cross(sub(b, a), sub(c, a))) > kDegenerateArea * longest * longest);
  }

  SurfaceMesh& out_;
  LoadReport& report_;
  std::unordered_map<PositionKey, uint32_t, PositionHash> index_;
  size_t welded_ = 0, non_triangles_ = 0;
  bool any_uv_ = false;  // some sub-mesh or the polygon file has texture coordinates
};

// assimp falls back to every importer it has when the one for the extension does not recognise
// the content (a broken .gltf went to its OpenGEX parser): only the importers of this extension
// are kept. UnregisterLoader does not free an importer, so it is deleted here.
void keep_only_importers_of(Assimp::Importer& importer, const std::string& extension) {
  for (size_t i = importer.GetImporterCount(); i-- > 0;) {
    const aiImporterDesc* info = importer.GetImporterInfo(i);
    std::istringstream names(
        info != nullptr && info->mFileExtensions != nullptr ? info->mFileExtensions : "");
    bool match = false;
    for (std::string name; names >> name;) match = match || "." + name == extension;
    if (match) continue;
    Assimp::BaseImporter* other = importer.GetImporter(i);
    importer.UnregisterLoader(other);
    delete other;
  }
}

void add_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent,
              SurfaceBuilder& builder, int depth) {
  if (depth > 256) throw InputError({"", 0, 0, ""}, "scene graph nested deeper than 256 nodes");
  aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    if (node.mMeshes[m] < scene.mNumMeshes)
      builder.add_mesh(*scene.mMeshes[node.mMeshes[m]], transform);
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    add_node(scene, *node.mChildren[c], transform, builder, depth + 1);
}

}  // namespace

SurfaceMesh load_surface(const std::string& path, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError({path, 0, 0, ""}, "no such file");
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  r.format = "surface:" + (extension.empty() ? std::string("?") : extension.substr(1));

  SurfaceMesh out;
  out.source = path;
  SurfaceBuilder builder(out, r);
  const std::string bytes = mesh_detail::read_file_bytes(path);
  // Never through assimp: PLY, OBJ, OFF and VTK (see surface_readers.hpp). A VTK file is legacy
  // or XML by its first bytes, whatever its extension says.
  if (mesh_detail::is_ply(path, bytes)) {
    builder.add_polygons(mesh_detail::read_ply(path, bytes));
  } else if (extension == ".obj") {
    builder.add_polygons(mesh_detail::read_obj(path, bytes));
  } else if (extension == ".off") {
    builder.add_polygons(mesh_detail::read_off(path, bytes));
  } else if (extension == ".vtk" || extension == ".vtp" || extension == ".vtu") {
    const size_t start = bytes.find_first_not_of(" \t\r\n");
    if (bytes.starts_with("# vtk DataFile")) {
      builder.add_polygons(mesh_detail::read_vtk_legacy_polydata(path, bytes));
    } else if (bytes.starts_with("\xEF\xBB\xBF") ||
               (start != std::string::npos && bytes[start] == '<')) {
      builder.add_polygons(mesh_detail::read_vtk_xml_polydata(path, bytes));
    } else {
      throw InputError({path, 1, 0, ""},
                       "not a VTK file: expected '# vtk DataFile' (legacy) or <VTKFile> (XML)");
    }
  } else {
    // assimp reads only what was checked first: its other importers are not, so they are refused.
    if (extension == ".stl") {
      mesh_detail::check_stl(path, bytes);
    } else if (extension == ".gltf" || extension == ".glb") {
      mesh_detail::check_gltf(path, bytes);
    } else {
      throw InputError({path, 0, 0, ""},
                       "unsupported surface format '" + extension +
                           "': expected .obj, .stl, .ply, .off, .vtk, .vtp, .gltf or .glb (or a "
                           "volume mesh)");
    }
    Assimp::Importer importer;
    keep_only_importers_of(importer, extension);
    const aiScene* scene = nullptr;
    try {
      scene = importer.ReadFile(path, aiProcess_JoinIdenticalVertices | aiProcess_Triangulate);
    } catch (const std::exception& e) {
      throw InputError({path, 0, 0, ""}, std::string("the surface importer failed: ") + e.what());
    }
    if (!scene || !scene->mRootNode) {
      throw InputError({path, 0, 0, ""},
                       std::string("cannot read as a surface mesh: ") + importer.GetErrorString());
    }
    try {
      add_node(*scene, *scene->mRootNode, aiMatrix4x4(), builder, 0);
    } catch (const InputError& e) {
      if (!e.where().file.empty()) throw;
      throw InputError({path, 0, 0, ""}, e.what());
    }
  }
  builder.finish();
  if (out.triangles.empty())
    throw InputError({path, 0, 0, ""}, "the file holds no (non-degenerate) triangles");
  check_closed(out, r);
  return out;
}

}  // namespace tacta
