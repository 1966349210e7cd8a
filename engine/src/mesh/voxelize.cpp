// A closed surface becomes a deformable body: a sparse grid of cubes (those inside the surface or
// touching it), each cut into 6 conforming tets, and the surface embedded by barycentric weights.
// Inside test: generalized winding number (Jacobson et al. 2013), robust to small holes; solid
// angles by the Van Oosterom-Strackee formula.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "mesh/geometry.hpp"
#include "mesh/grid_tets.hpp"
#include "tacta/mesh_build.hpp"

namespace tacta {

namespace {

using mesh_detail::P3;
using mesh_detail::point;

constexpr int64_t kMaxCells = 2'000'000;  // 12 million tets: far past what a haptic loop steps

// Separating-axis test of a triangle (relative to a box centre) against a box of half-edge half.
bool triangle_touches_box(const P3 tri[3], double half) {
  const P3 edges[3] = {tri[1] - tri[0], tri[2] - tri[1], tri[0] - tri[2]};
  P3 axes[13] = {{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}, cross(edges[0], edges[1])};
  int count = 4;
  for (const P3& e : edges) {
    for (int a = 0; a < 3; ++a) {
      P3 unit{{0, 0, 0}};
      unit[static_cast<size_t>(a)] = 1;
      axes[count++] = cross(unit, e);
    }
  }
  for (const P3& axis : axes) {
    double radius = half * (std::abs(axis[0]) + std::abs(axis[1]) + std::abs(axis[2]));
    if (radius == 0) continue;  // parallel edges give a null axis, which separates nothing
    double p0 = dot(axis, tri[0]), p1 = dot(axis, tri[1]), p2 = dot(axis, tri[2]);
    if (std::min({p0, p1, p2}) > radius || std::max({p0, p1, p2}) < -radius) return false;
  }
  return true;
}

double winding_number(const SurfaceMesh& s, const P3& p) {
  double total = 0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    P3 a = point(s.positions, s.triangles[3 * t]) - p, b = point(s.positions, s.triangles[3 * t + 1]) - p,
       c = point(s.positions, s.triangles[3 * t + 2]) - p;
    double la = norm(a), lb = norm(b), lc = norm(c);
    double numerator = mesh_detail::triple(a, b, c);
    double denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * std::numbers::pi);
}

struct Grid {
  P3 origin;
  double h = 0;
  int64_t n[3] = {0, 0, 0};
  int64_t cell(int64_t i, int64_t j, int64_t k) const { return i + n[0] * (j + n[1] * k); }
  int64_t clamp_index(double x, int axis) const {
    auto i = static_cast<int64_t>(std::floor((x - origin[static_cast<size_t>(axis)]) / h));
    return std::clamp<int64_t>(i, 0, n[axis] - 1);
  }
};

void mark_touched_cells(const SurfaceMesh& s, const Grid& g, std::vector<char>& active) {
  const double half = 0.5 * g.h * (1 + 1e-9);  // a hair larger: a vertex on a cell face touches both cells
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    P3 tri[3];
    for (int k = 0; k < 3; ++k) tri[k] = point(s.positions, s.triangles[3 * t + static_cast<size_t>(k)]);
    int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      auto ua = static_cast<size_t>(a);
      lo[a] = g.clamp_index(std::min({tri[0][ua], tri[1][ua], tri[2][ua]}) - 1e-9 * g.h, a);
      hi[a] = g.clamp_index(std::max({tri[0][ua], tri[1][ua], tri[2][ua]}) + 1e-9 * g.h, a);
    }
    for (int64_t k = lo[2]; k <= hi[2]; ++k) {
      for (int64_t j = lo[1]; j <= hi[1]; ++j) {
        for (int64_t i = lo[0]; i <= hi[0]; ++i) {
          int64_t c = g.cell(i, j, k);
          if (active[static_cast<size_t>(c)]) continue;
          P3 centre = g.origin + P3{{(static_cast<double>(i) + 0.5) * g.h, (static_cast<double>(j) + 0.5) * g.h,
                                     (static_cast<double>(k) + 0.5) * g.h}};
          P3 local[3] = {tri[0] - centre, tri[1] - centre, tri[2] - centre};
          if (triangle_touches_box(local, half)) active[static_cast<size_t>(c)] = 1;
        }
      }
    }
  }
}

// A run of untouched cells along x lies on one side of the surface: one winding number per run.
void mark_inside_cells(const SurfaceMesh& s, const Grid& g, std::vector<char>& active) {
  std::vector<char> touched = active;
  for (int64_t k = 0; k < g.n[2]; ++k) {
    for (int64_t j = 0; j < g.n[1]; ++j) {
      for (int64_t i = 0; i < g.n[0];) {
        if (touched[static_cast<size_t>(g.cell(i, j, k))]) {
          ++i;
          continue;
        }
        int64_t end = i;
        while (end < g.n[0] && !touched[static_cast<size_t>(g.cell(end, j, k))]) ++end;
        P3 centre = g.origin + P3{{(static_cast<double>(i) + 0.5) * g.h, (static_cast<double>(j) + 0.5) * g.h,
                                   (static_cast<double>(k) + 0.5) * g.h}};
        if (std::abs(winding_number(s, centre)) > 0.5) {
          for (int64_t r = i; r < end; ++r) active[static_cast<size_t>(g.cell(r, j, k))] = 1;
        }
        i = end;
      }
    }
  }
}

}  // namespace

VolumeMesh voxelize(const SurfaceMesh& closed, double cell_size, LoadReport* report) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  const std::string& source = closed.source;
  if (!(cell_size > 0) || !std::isfinite(cell_size)) throw InputError({source, 0, 0, ""}, "voxel size must be positive and finite");
  if (closed.triangle_count() == 0) throw InputError({source, 0, 0, ""}, "cannot voxelise a surface with no triangles");
  check_closed(closed, r);
  if (!r.closed()) {
    r.warnings.push_back("the surface is not closed (" + std::to_string(r.boundary_edges) + " open edges, " +
                         std::to_string(r.nonmanifold_edges) + " non-manifold edges); its inside is a best guess");
  }
  P3 lo{{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()}};
  P3 hi = -1.0 * lo;
  for (size_t v = 0; v < closed.vertex_count(); ++v) {
    for (size_t a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], closed.positions[3 * v + a]);
      hi[a] = std::max(hi[a], closed.positions[3 * v + a]);
    }
  }
  Grid g;
  g.h = cell_size;
  int64_t cells = 1;
  for (size_t a = 0; a < 3; ++a) {
    g.origin[a] = lo[a] - 0.5 * cell_size;  // half a cell of margin: no vertex on the grid's outer faces
    double count = std::ceil((hi[a] - lo[a]) / cell_size) + 1;
    if (!(count <= static_cast<double>(kMaxCells))) throw InputError({source, 0, 0, ""}, "voxel size too small for the surface");
    g.n[a] = static_cast<int64_t>(count);
    cells *= g.n[a];
    if (cells > kMaxCells) {
      throw InputError({source, 0, 0, ""}, "voxel size " + std::to_string(cell_size) + " m gives more than 2 million cells");
    }
  }
  std::vector<char> active(static_cast<size_t>(cells), 0);
  mark_touched_cells(closed, g, active);
  mark_inside_cells(closed, g, active);

  VolumeMesh mesh;
  mesh.source = source + " (voxelised)";
  const int64_t nodes_x = g.n[0] + 1, nodes_y = g.n[1] + 1;
  std::vector<uint32_t> node_of(static_cast<size_t>(nodes_x * nodes_y * (g.n[2] + 1)), UINT32_MAX);
  std::vector<uint32_t> first_tet(static_cast<size_t>(cells), UINT32_MAX);
  for (int64_t k = 0; k < g.n[2]; ++k) {
    for (int64_t j = 0; j < g.n[1]; ++j) {
      for (int64_t i = 0; i < g.n[0]; ++i) {
        if (!active[static_cast<size_t>(g.cell(i, j, k))]) continue;
        uint32_t corner[8];
        for (int64_t c = 0; c < 8; ++c) {
          int64_t ni = i + (c & 1), nj = j + ((c >> 1) & 1), nk = k + ((c >> 2) & 1);
          uint32_t& id = node_of[static_cast<size_t>(ni + nodes_x * (nj + nodes_y * nk))];
          if (id == UINT32_MAX) {
            id = static_cast<uint32_t>(mesh.node_count());
            mesh.positions.insert(mesh.positions.end(), {g.origin[0] + static_cast<double>(ni) * g.h,
                                                         g.origin[1] + static_cast<double>(nj) * g.h,
                                                         g.origin[2] + static_cast<double>(nk) * g.h});
          }
          corner[c] = id;
        }
        first_tet[static_cast<size_t>(g.cell(i, j, k))] = static_cast<uint32_t>(mesh.tet_count());
        mesh_detail::append_cell_tets(corner, mesh.tets);
      }
    }
  }

  Embedding e;
  e.surface = closed;
  e.element.resize(closed.vertex_count());
  e.weights.resize(4 * closed.vertex_count());
  for (size_t v = 0; v < closed.vertex_count(); ++v) {
    P3 p = point(closed.positions, static_cast<uint32_t>(v));
    int64_t idx[3];
    for (int a = 0; a < 3; ++a) idx[a] = g.clamp_index(p[static_cast<size_t>(a)], a);
    int64_t cell = g.cell(idx[0], idx[1], idx[2]);
    if (first_tet[static_cast<size_t>(cell)] == UINT32_MAX) {
      // Rounding left the vertex's own cell empty: take the nearest active cell (extrapolating).
      double best = std::numeric_limits<double>::infinity();
      for (int64_t c = 0; c < cells; ++c) {
        if (first_tet[static_cast<size_t>(c)] == UINT32_MAX) continue;
        int64_t ci = c % g.n[0], cj = (c / g.n[0]) % g.n[1], ck = c / (g.n[0] * g.n[1]);
        double d = std::hypot(static_cast<double>(ci - idx[0]), static_cast<double>(cj - idx[1]), static_cast<double>(ck - idx[2]));
        if (d < best) {
          best = d;
          cell = c;
        }
      }
    }
    int64_t ci = cell % g.n[0], cj = (cell / g.n[0]) % g.n[1], ck = cell / (g.n[0] * g.n[1]);
    double u = (p[0] - g.origin[0]) / g.h - static_cast<double>(ci), w1 = (p[1] - g.origin[1]) / g.h - static_cast<double>(cj),
           w2 = (p[2] - g.origin[2]) / g.h - static_cast<double>(ck);
    uint32_t tet = first_tet[static_cast<size_t>(cell)] + static_cast<uint32_t>(mesh_detail::cell_tet_of(u, w1, w2));
    const uint32_t* n = &mesh.tets[4 * size_t{tet}];
    auto weights = mesh_detail::barycentric(p, point(mesh.positions, n[0]), point(mesh.positions, n[1]),
                                            point(mesh.positions, n[2]), point(mesh.positions, n[3]));
    e.element[v] = tet;
    std::copy(weights.begin(), weights.end(), e.weights.begin() + static_cast<std::ptrdiff_t>(4 * v));
  }
  mesh.embedding = std::move(e);
  finalize(mesh, &r);
  return mesh;
}

}  // namespace tacta
