// Fuzzes cutting's topology core (engine/src/topology/cut_mesh.hpp): a small box grid or ball, its
// nodes moved at random, then a few cuts in either mode with blades the bytes choose (random
// triangles, planes on grid faces or through nodes, flat or non-finite triangles). After each
// cut every invariant that holds for any blade is checked, and a broken one aborts: the mesh
// passes topology_problems, sources are in range and every tet keeps its nodes (or their copies),
// the volume is kept (separation) or less the removed tets' exactly (removal), and the embedded
// surface carried over the cut is sized right and still gives back its rest positions.
#include "topology/cut_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "tacta/embedded_surface.hpp"
#include "tacta/mesh_build.hpp"
#include "tacta/vec3.hpp"

namespace {

using tacta::Vec3;

// The input read front to back; past its end every read is 0.
class Bytes {
 public:
  Bytes(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  double unit() { return (byte() * 256.0 + byte()) / 65535.0; }  // [0, 1]

 private:
  const uint8_t* data_;
  size_t size_, at_ = 0;
};

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz_cut: %s\n", what.c_str());
  std::abort();
}
void require(bool ok, const char* what) {
  if (!ok) fail(what);
}

double tet_volume(const tacta::VolumeMesh& m, size_t t) {
  const uint32_t* n = &m.tets[4 * t];
  const Vec3 a = tacta::point_at(m.positions.data(), n[0]);
  return tacta::triple(tacta::sub(tacta::point_at(m.positions.data(), n[1]), a),
                       tacta::sub(tacta::point_at(m.positions.data(), n[2]), a),
                       tacta::sub(tacta::point_at(m.positions.data(), n[3]), a)) /
         6.0;
}

double volume(const tacta::VolumeMesh& m) {
  double v = 0;
  for (size_t t = 0; t < m.tet_count(); ++t) v += tet_volume(m, t);
  return v;
}

void push(std::vector<double>& out, const Vec3& p) { out.insert(out.end(), p.begin(), p.end()); }

// A plane through p with normal n (unit), as two triangles reaching `reach` m from p.
void plane(std::vector<double>& out, const Vec3& p, const Vec3& n, double reach) {
  const Vec3 u =
      tacta::normalized(tacta::cross(n, std::abs(n[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  const Vec3 v = tacta::cross(n, u);
  auto at = [&](double a, double b) {
    return tacta::add(p, tacta::add(tacta::scaled(u, a * reach), tacta::scaled(v, b * reach)));
  };
  for (const Vec3& q : {at(-1, -1), at(1, -1), at(1, 1), at(-1, -1), at(1, 1), at(-1, 1)})
    push(out, q);
}

// The blade of one cut, in the frame of `x` (deformed positions, 3 per node).
std::vector<double> make_blade(Bytes& in, const std::vector<double>& x, double h, double extent) {
  const size_t nodes = x.size() / 3;
  Vec3 lo = tacta::point_at(x.data(), 0), hi = lo;
  for (size_t n = 0; n < nodes; ++n)
    for (size_t a = 0; a < 3; ++a)
      lo[a] = std::min(lo[a], x[3 * n + a]), hi[a] = std::max(hi[a], x[3 * n + a]);
  auto inside = [&] {  // a point of the body's box, grown by a fifth
    Vec3 p;
    for (size_t a = 0; a < 3; ++a)
      p[a] = lo[a] - 0.2 * extent + in.unit() * (hi[a] - lo[a] + 0.4 * extent);
    return p;
  };
  auto node = [&] { return tacta::point_at(x.data(), (in.byte() * 256u + in.byte()) % nodes); };
  std::vector<double> blade;
  const int kind = in.byte() % 5;
  if (kind == 0) {  // random triangles
    for (int t = 1 + in.byte() % 4; t > 0; --t)
      for (int k = 0; k < 3; ++k) push(blade, inside());
  } else if (kind == 1) {  // a plane on a grid plane of the rest box, or a little off it
    const size_t axis = in.byte() % 3;
    Vec3 n{0, 0, 0}, p = lo;
    n[axis] = 1;
    p[axis] = lo[axis] + h * (in.byte() % 5) + (in.byte() % 2 ? 0.0 : h * in.unit());
    plane(blade, p, n, 4 * extent);
  } else if (kind == 2) {  // a triangle through three nodes, grown about their centre
    const Vec3 a = node(), b = node(), c = node();
    const Vec3 m = tacta::scaled(tacta::add(a, tacta::add(b, c)), 1.0 / 3);
    const double grow = 1 + 20 * in.unit();
    for (const Vec3& q : {a, b, c})
      push(blade, tacta::add(m, tacta::scaled(tacta::sub(q, m), grow)));
  } else if (kind == 3) {  // a plane through a node, in a direction the bytes give
    const Vec3 n =
        tacta::normalized({in.unit() - 0.5, in.unit() - 0.5, in.unit() - 0.5}, {0, 0, 1});
    plane(blade, node(), n, 4 * extent);
  } else {  // flat, repeated or non-finite corners
    const Vec3 a = inside(), b = inside();
    const double s = in.unit();
    for (const Vec3& q : {a, b, tacta::add(a, tacta::scaled(tacta::sub(b, a), s)), a, a, a})
      push(blade, q);
    if (in.byte() % 2) blade[in.byte() % blade.size()] = std::numeric_limits<double>::quiet_NaN();
  }
  return blade;
}

void check_surface(const tacta::CutSurface& cut, const tacta::VolumeMesh& mesh, double size) {
  const tacta::EmbeddedSurface& s = cut.surface;
  const size_t v = s.vertex_count(), t = s.triangle_count();
  require(s.rest_positions.size() == 3 * v && s.tet.size() == v && s.nodes.size() == 4 * v &&
              s.weights.size() == 4 * v && s.positions.size() == 3 * v &&
              s.normals.size() == 3 * v && s.triangles.size() == 3 * t &&
              cut.cut_triangle.size() == t &&
              (s.corner_uvs.empty() || s.corner_uvs.size() == 6 * t),
          "surface arrays of the wrong size");
  for (uint32_t i : s.triangles) require(i < v, "surface triangle past its vertices");
  for (size_t i = 0; i < v; ++i) {
    require(s.tet[i] < mesh.tet_count(), "surface vertex on a tet past the mesh");
    for (size_t k = 0; k < 4; ++k)
      require(s.nodes[4 * i + k] == mesh.tets[4 * size_t{s.tet[i]} + k],
              "surface vertex nodes are not its tet's");
    double p[3];
    tacta::interpolate_vertex(s, i, mesh.positions.data(), p);
    for (size_t a = 0; a < 3; ++a)
      require(std::abs(p[a] - s.rest_positions[3 * i + a]) <= 1e-9 * size,
              "surface vertex no longer at its rest position");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Bytes in(data, size);
  const uint8_t shape = in.byte();
  tacta::VolumeMesh mesh;
  double h = 1;  // m, a cell
  if (shape % 8 == 7) {
    mesh = tacta::make_sphere(1.0, {0, 0, 0}, (shape / 8) % 2);
    h = 0.5;
  } else {
    const std::array<int, 3> cells = {1 + in.byte() % 4, 1 + in.byte() % 4, 1 + in.byte() % 4};
    mesh = tacta::make_box_grid({double(cells[0]), double(cells[1]), double(cells[2])}, cells,
                                {0, 0, 0});
  }
  const double extent = 4 * h;
  // The surface the cuts carry: the mesh's own boundary, bound to its tets.
  tacta::SurfaceMesh boundary;
  boundary.positions = mesh.positions;
  boundary.triangles = mesh.triangles;
  mesh.embedding = tacta::bind_surface_to_tets(boundary, mesh);
  tacta::EmbeddedSurface surface = tacta::make_embedded_surface(mesh);
  mesh.embedding.reset();
  std::vector<uint8_t> surface_cut, mesh_cut;
  // Deformed nodes: the rest moved by up to `jitter` of a cell, at random.
  const double jitter = 0.4 * h * in.unit();
  std::minstd_rand random(in.byte() + 1u);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  std::vector<double> x = mesh.positions;
  for (double& c : x) c += offset(random);

  for (int cuts = 1 + in.byte() % 4; cuts > 0; --cuts) {
    const tacta::CutMode mode = in.byte() % 2 ? tacta::CutMode::kSeparate : tacta::CutMode::kRemove;
    const std::vector<double> blade = make_blade(in, x, h, extent);
    const tacta::CutResult r = tacta::cut_mesh(mesh, mesh_cut, x, blade, mode);
    const tacta::TopologyEdit& e = r.edit;
    if (!r.refused.empty()) {
      require(mode == tacta::CutMode::kRemove && r.refused.find("every tet") != std::string::npos,
              "a cut of a good mesh refused for another reason");
      require(!e.changed() && e.mesh.tets == mesh.tets, "a refused cut changed the mesh");
    }
    const std::vector<std::string> problems = tacta::topology_problems(e.mesh);
    if (!problems.empty()) fail("topology: " + problems[0]);
    require(
        e.node_source.size() == e.mesh.node_count() && e.tet_source.size() == e.mesh.tet_count(),
        "sources of the wrong size");
    require(e.cut_triangle.size() == e.mesh.triangles.size() / 3, "cut marks of the wrong size");
    for (uint32_t n : e.node_source) require(n < mesh.node_count(), "node source out of range");
    for (size_t t = 0; t < e.tet_source.size(); ++t) {
      require(
          e.tet_source[t] < mesh.tet_count() && (t == 0 || e.tet_source[t] > e.tet_source[t - 1]),
          "tet sources out of range or order");
      for (size_t k = 0; k < 4; ++k)
        require(e.node_source[e.mesh.tets[4 * t + k]] == mesh.tets[4 * size_t{e.tet_source[t]} + k],
                "a tet lost one of its nodes");
    }
    // Volume bookkeeping (rest, m^3): separation keeps it, removal loses its tets' exactly.
    double removed = 0;
    std::vector<uint8_t> kept(mesh.tet_count(), 0);
    for (uint32_t t : e.tet_source) kept[t] = 1;
    for (size_t t = 0; t < mesh.tet_count(); ++t)
      if (!kept[t]) removed += tet_volume(mesh, t);
    const double before = volume(mesh);
    require(std::abs(volume(e.mesh) - (before - removed)) <= 1e-12 * before, "volume not kept");
    require(e.tets_removed == mesh.tet_count() - e.mesh.tet_count(), "tets_removed miscounted");
    if (mode == tacta::CutMode::kSeparate) {
      require(e.tets_removed == 0 && e.nodes_removed == 0, "separation removed something");
      require(e.nodes_added == e.mesh.node_count() - mesh.node_count(), "nodes_added miscounted");
    } else {
      require(e.nodes_added == 0 && e.faces_separated == 0, "removal separated something");
      require(e.nodes_removed == mesh.node_count() - e.mesh.node_count(),
              "nodes_removed miscounted");
    }
    require(e.changed() || e.mesh.tets == mesh.tets, "an unchanged edit changed the tets");
    const tacta::CutSurface carried = tacta::cut_embedded_surface(surface, surface_cut, mesh, e);
    check_surface(carried, e.mesh, extent);
    // The next cut starts from this one; copies stand where their source stood.
    std::vector<double> next_x(3 * e.mesh.node_count());
    for (size_t n = 0; n < e.node_source.size(); ++n)
      for (size_t a = 0; a < 3; ++a) next_x[3 * n + a] = x[3 * size_t{e.node_source[n]} + a];
    x = std::move(next_x);
    mesh = e.mesh;
    mesh_cut = e.cut_triangle;
    surface = carried.surface;
    surface_cut = carried.cut_triangle;
  }
  return 0;
}
