// Triangle surfaces through assimp. assimp's own vertex joining keeps vertices apart when their
// normals or texture coordinates differ (every STL corner, OBJ seams), so positions are welded
// again here, exactly, across all sub-meshes: a body's surface must be one connected mesh.
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>
#include <unordered_map>

#include "mesh/geometry.hpp"
#include "mesh/ply_check.hpp"
#include "tacta/mesh_io.hpp"

namespace tacta {

namespace {

using mesh_detail::P3;

constexpr double kDegenerateArea = 1e-12;  // |cross| below this times (longest edge)^2 is a flat triangle

struct PositionKey {
  uint64_t bits[3];
  bool operator==(const PositionKey& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
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
      double xyz[3] = {static_cast<double>(p.x) + 0.0, static_cast<double>(p.y) + 0.0, static_cast<double>(p.z) + 0.0};
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) {
        throw InputError({out_.source, 0, 0, ""}, "vertex " + std::to_string(v) + " of mesh '" + mesh.mName.C_Str() +
                                                      "' has a NaN or infinite coordinate");
      }
      PositionKey key;
      std::memcpy(key.bits, xyz, sizeof key.bits);
      auto [it, inserted] = index_.emplace(key, static_cast<uint32_t>(out_.vertex_count()));
      if (inserted) {
        out_.positions.insert(out_.positions.end(), xyz, xyz + 3);
      } else {
        ++welded_;
      }
      local[v] = it->second;
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
        if (i >= mesh.mNumVertices) throw InputError({out_.source, 0, 0, ""}, "a face refers to a vertex that does not exist");
        t[k] = local[i];
        if (uv != nullptr) corner_uv[2 * k] = uv[i].x, corner_uv[2 * k + 1] = uv[i].y;
      }
      if (mirrored) {
        std::swap(t[1], t[2]);
        std::swap(corner_uv[2], corner_uv[4]);
        std::swap(corner_uv[3], corner_uv[5]);
      }
      if (degenerate(t)) {
        ++report_.degenerate_triangles;
        continue;
      }
      out_.triangles.insert(out_.triangles.end(), t, t + 3);
      out_.corner_uvs.insert(out_.corner_uvs.end(), corner_uv, corner_uv + 6);
    }
  }

  void finish() {
    if (!any_uv_) out_.corner_uvs.clear();
    report_.welded_vertices += welded_;
    if (report_.degenerate_triangles > 0) {
      report_.warnings.push_back(std::to_string(report_.degenerate_triangles) +
                                 " degenerate triangles (zero area or a repeated vertex) were dropped");
    }
    if (non_triangles_ > 0) report_.warnings.push_back(std::to_string(non_triangles_) + " points or lines were ignored");
  }

 private:
  bool degenerate(const uint32_t t[3]) const {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
    P3 a = mesh_detail::point(out_.positions, t[0]), b = mesh_detail::point(out_.positions, t[1]),
       c = mesh_detail::point(out_.positions, t[2]);
    double longest = std::max({norm(b - a), norm(c - b), norm(a - c)});
    return !(norm(cross(b - a, c - a)) > kDegenerateArea * longest * longest);
  }

  SurfaceMesh& out_;
  LoadReport& report_;
  std::unordered_map<PositionKey, uint32_t, PositionHash> index_;
  size_t welded_ = 0, non_triangles_ = 0;
  bool any_uv_ = false;  // some sub-mesh has texture coordinates
};

void add_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, SurfaceBuilder& builder, int depth) {
  if (depth > 256) throw InputError({"", 0, 0, ""}, "scene graph nested deeper than 256 nodes");
  aiMatrix4x4 transform = parent * node.mTransformation;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    if (node.mMeshes[m] < scene.mNumMeshes) builder.add_mesh(*scene.mMeshes[node.mMeshes[m]], transform);
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) add_node(scene, *node.mChildren[c], transform, builder, depth + 1);
}

}  // namespace

SurfaceMesh load_surface(const std::string& path, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError({path, 0, 0, ""}, "no such file");
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  r.format = "surface:" + (extension.empty() ? std::string("?") : extension.substr(1));

  mesh_detail::check_ply_complete(path);  // assimp hangs or aborts on a PLY cut short
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path, aiProcess_JoinIdenticalVertices | aiProcess_Triangulate);
  } catch (const std::exception& e) {
    throw InputError({path, 0, 0, ""}, std::string("the surface importer failed: ") + e.what());
  }
  if (!scene || !scene->mRootNode) {
    throw InputError({path, 0, 0, ""}, std::string("cannot read as a surface mesh: ") + importer.GetErrorString());
  }
  SurfaceMesh out;
  out.source = path;
  SurfaceBuilder builder(out, r);
  try {
    add_node(*scene, *scene->mRootNode, aiMatrix4x4(), builder, 0);
  } catch (const InputError& e) {
    if (!e.where().file.empty()) throw;
    throw InputError({path, 0, 0, ""}, e.what());
  }
  builder.finish();
  if (out.triangles.empty()) throw InputError({path, 0, 0, ""}, "the file holds no (non-degenerate) triangles");
  check_closed(out, r);
  return out;
}

}  // namespace tacta
