// topology_problems: the invariants every mesh a cut makes must keep, checked from the tets up
// (not through the builders that made the boundary and edges).
#include <algorithm>
#include <array>
#include <iterator>
#include <string>
#include <vector>

#include "mesh/geometry.hpp"
#include "mesh/tet_faces.hpp"
#include "tacta/vec3.hpp"
#include "topology/cut_mesh.hpp"

namespace tacta {

namespace {

using mesh_detail::kTetFaces;
using mesh_detail::TetFace;

// "3 tets have ... (first: tet 7)" when count > 0.
void report(std::vector<std::string>& problems, size_t count, const std::string& what,
            const std::string& first) {
  if (count == 0) return;
  problems.push_back(std::to_string(count) + " " + what + " (first: " + first + ")");
}

// The outward faces (one tet only), by key; each with its winding.
struct BoundaryFace {
  std::array<uint32_t, 3> key, winding;
  bool seen = false;
};

bool same_winding(const std::array<uint32_t, 3>& a, const uint32_t* b) {
  for (size_t r = 0; r < 3; ++r)
    if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return true;
  return false;
}

void check_faces(const VolumeMesh& mesh, std::vector<std::string>& problems) {
  const std::vector<TetFace> faces = mesh_detail::sorted_tet_faces(mesh.tets);
  std::vector<BoundaryFace> boundary;
  size_t crowded = 0;
  std::string first_crowded;
  for (size_t i = 0; i < faces.size();) {
    size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j - i > 2 && crowded++ == 0)
      first_crowded = "nodes " + std::to_string(faces[i].key[0]) + " " +
                      std::to_string(faces[i].key[1]) + " " + std::to_string(faces[i].key[2]) +
                      ", " + std::to_string(j - i) + " tets";
    if (j - i == 1) {
      const uint32_t t = faces[i].tet(), f = faces[i].order % 4;
      BoundaryFace b{faces[i].key, {}};
      for (size_t k = 0; k < 3; ++k) b.winding[k] = mesh.tets[4 * size_t{t} + kTetFaces[f][k]];
      boundary.push_back(b);
    }
    i = j;
  }
  report(problems, crowded, "faces are shared by more than two tets", first_crowded);
  size_t stray = 0, inward = 0, repeated = 0;
  std::string first_stray, first_inward, first_repeated;
  for (size_t i = 0; i < mesh.triangles.size() / 3; ++i) {
    const uint32_t* v = &mesh.triangles[3 * i];
    std::array<uint32_t, 3> key = {v[0], v[1], v[2]};
    std::sort(key.begin(), key.end());
    const auto at = std::lower_bound(
        boundary.begin(), boundary.end(), key,
        [](const BoundaryFace& b, const std::array<uint32_t, 3>& k) { return b.key < k; });
    const std::string name = "triangle " + std::to_string(i);
    if (at == boundary.end() || at->key != key) {
      if (stray++ == 0) first_stray = name;
    } else if (at->seen) {
      if (repeated++ == 0) first_repeated = name;
    } else {
      at->seen = true;
      if (!same_winding(at->winding, v) && inward++ == 0) first_inward = name;
    }
  }
  report(problems, stray, "boundary triangles are not a face of exactly one tet", first_stray);
  report(problems, repeated, "boundary triangles repeat a face", first_repeated);
  report(problems, inward, "boundary triangles are not wound outward", first_inward);
  const auto missing =
      std::find_if(boundary.begin(), boundary.end(), [](const BoundaryFace& b) { return !b.seen; });
  if (missing != boundary.end())
    report(problems,
           static_cast<size_t>(std::count_if(boundary.begin(), boundary.end(),
                                             [](const BoundaryFace& b) { return !b.seen; })),
           "faces of one tet are missing from the boundary triangles",
           "nodes " + std::to_string(missing->key[0]) + " " + std::to_string(missing->key[1]) +
               " " + std::to_string(missing->key[2]));
}

void check_edges(const VolumeMesh& mesh, std::vector<std::string>& problems) {
  std::vector<std::array<uint32_t, 2>> expected, given;
  for (size_t t = 0; t < mesh.tet_count(); ++t)
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i + 1; j < 4; ++j) {
        const uint32_t a = mesh.tets[4 * t + i], b = mesh.tets[4 * t + j];
        expected.push_back({std::min(a, b), std::max(a, b)});
      }
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  size_t unordered = 0;
  for (size_t e = 0; e < mesh.edges.size() / 2; ++e) {
    const uint32_t a = mesh.edges[2 * e], b = mesh.edges[2 * e + 1];
    if (!(a < b)) ++unordered;
    given.push_back({std::min(a, b), std::max(a, b)});
  }
  std::sort(given.begin(), given.end());
  const size_t before = given.size();
  given.erase(std::unique(given.begin(), given.end()), given.end());
  if (unordered > 0)
    problems.push_back(std::to_string(unordered) + " edges are not written smaller node first");
  if (before != given.size())
    problems.push_back(std::to_string(before - given.size()) + " edges are listed twice");
  std::vector<std::array<uint32_t, 2>> missing, extra;
  std::set_difference(expected.begin(), expected.end(), given.begin(), given.end(),
                      std::back_inserter(missing));
  std::set_difference(given.begin(), given.end(), expected.begin(), expected.end(),
                      std::back_inserter(extra));
  auto edge = [](const std::array<uint32_t, 2>& e) {
    return "nodes " + std::to_string(e[0]) + " " + std::to_string(e[1]);
  };
  if (!missing.empty())
    report(problems, missing.size(), "tet edges are missing from the edge list", edge(missing[0]));
  if (!extra.empty())
    report(problems, extra.size(), "listed edges are no tet's edge", edge(extra[0]));
}

}  // namespace

std::vector<std::string> topology_problems(const VolumeMesh& mesh) {
  std::vector<std::string> problems;
  if (mesh.dimension != 3)
    problems.push_back("dimension is " + std::to_string(mesh.dimension) + ", 3 expected");
  if (mesh.positions.size() % 3 != 0) problems.push_back("positions are not 3 per node");
  if (mesh.tets.size() % 4 != 0) problems.push_back("tet indices are not 4 per tet");
  if (mesh.triangles.size() % 3 != 0) problems.push_back("triangle indices are not 3 per triangle");
  if (mesh.edges.size() % 2 != 0) problems.push_back("edge indices are not 2 per edge");
  if (mesh.tets.empty()) problems.push_back("the mesh has no tets");
  const size_t nodes = mesh.node_count();
  for (const auto& [indices, what] :
       {std::pair{&mesh.tets, "tet"}, {&mesh.triangles, "triangle"}, {&mesh.edges, "edge"}}) {
    const auto past =
        std::find_if(indices->begin(), indices->end(), [&](uint32_t n) { return n >= nodes; });
    if (past != indices->end())
      problems.push_back(std::string(what) + " indices name node " + std::to_string(*past) +
                         ", past the mesh's " + std::to_string(nodes));
  }
  if (!problems.empty()) return problems;  // the checks below index by these arrays

  size_t flat = 0;
  std::string first_flat;
  std::vector<uint8_t> used(nodes, 0);
  for (size_t t = 0; t < mesh.tet_count(); ++t) {
    const uint32_t* n = &mesh.tets[4 * t];
    Vec3 x[4];
    for (size_t k = 0; k < 4; ++k) x[k] = point_at(mesh.positions.data(), n[k]), used[n[k]] = 1;
    double longest = 0;
    for (size_t i = 0; i < 4; ++i)
      for (size_t j = i + 1; j < 4; ++j) longest = std::max(longest, distance(x[i], x[j]));
    const double six_volume = triple(sub(x[1], x[0]), sub(x[2], x[0]), sub(x[3], x[0]));
    if (!(six_volume > mesh_detail::kFlatVolume * longest * longest * longest) && flat++ == 0)
      first_flat = "tet " + std::to_string(t);
  }
  report(problems, flat, "tets have no positive volume at rest", first_flat);
  const auto orphan = std::find(used.begin(), used.end(), uint8_t{0});
  if (orphan != used.end())
    report(problems, static_cast<size_t>(std::count(used.begin(), used.end(), uint8_t{0})),
           "nodes are in no tet", "node " + std::to_string(orphan - used.begin()));
  check_faces(mesh, problems);
  check_edges(mesh, problems);
  return problems;
}

}  // namespace tacta
