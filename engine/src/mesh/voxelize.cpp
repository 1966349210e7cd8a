// A closed surface becomes a deformable body: a sparse grid of cubes (those inside the surface or
// touching it), each cut into 6 conforming tets, and the surface embedded by barycentric weights.
// Inside test: generalized winding number (Jacobson et al. 2013), robust to small holes; solid
// angles by the Van Oosterom-Strackee formula.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "mesh/geometry.hpp"
#include "mesh/grid_tets.hpp"
#include "tacta/mesh_build.hpp"

namespace tacta {

namespace {

using mesh_detail::point;

constexpr int64_t kMaxCells = 2'000'000;  // 12 million tets: far past what a haptic loop steps

// Separating-axis test of a triangle (relative to a box centre) against a box of half-edge half.
bool triangle_touches_box(const Vec3 tri[3], double half) {
  const Vec3 edges[3] = {sub(tri[1], tri[0]), sub(tri[2], tri[1]), sub(tri[0], tri[2])};
  Vec3 axes[13] = {{{1, 0, 0}}, {{0, 1, 0}}, {{0, 0, 1}}, cross(edges[0], edges[1])};
  int count = 4;
  for (const Vec3& e : edges) {
    for (int a = 0; a < 3; ++a) {
      Vec3 unit{{0, 0, 0}};
      unit[static_cast<size_t>(a)] = 1;
      axes[count++] = cross(unit, e);
    }
  }
  for (const Vec3& axis : axes) {
    double radius = half * (std::abs(axis[0]) + std::abs(axis[1]) + std::abs(axis[2]));
    if (radius == 0) continue;  // parallel edges give a null axis, which separates nothing
    double p0 = dot(axis, tri[0]), p1 = dot(axis, tri[1]), p2 = dot(axis, tri[2]);
    if (std::min({p0, p1, p2}) > radius || std::max({p0, p1, p2}) < -radius) return false;
  }
  return true;
}

double winding_number(const SurfaceMesh& s, const Vec3& p) {
  double total = 0;
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    Vec3 a = sub(point(s.positions, s.triangles[3 * t]), p),
         b = sub(point(s.positions, s.triangles[3 * t + 1]), p),
         c = sub(point(s.positions, s.triangles[3 * t + 2]), p);
    double la = norm(a), lb = norm(b), lc = norm(c);
    double numerator = triple(a, b, c);
    double denominator = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * std::numbers::pi);
}

struct Grid {
  Vec3 origin;
  double h = 0;
  int64_t n[3] = {0, 0, 0};
  int64_t cell(int64_t i, int64_t j, int64_t k) const { return i + n[0] * (j + n[1] * k); }
  int64_t clamp_index(double x, int axis) const {
    auto i = static_cast<int64_t>(std::floor((x - origin[static_cast<size_t>(axis)]) / h));
    return std::clamp<int64_t>(i, 0, n[axis] - 1);
  }
};

void mark_touched_cells(const SurfaceMesh& s, const Grid& g, std::vector<char>& active) {
  const double half =
      0.5 * g.h * (1 + 1e-9);  // a hair larger: a vertex on a cell face touches both cells
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    Vec3 tri[3];
    for (int k = 0; k < 3; ++k)
      tri[k] = point(s.positions, s.triangles[3 * t + static_cast<size_t>(k)]);
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
          Vec3 centre = add(g.origin, Vec3{(static_cast<double>(i) + 0.5) * g.h,
                                           (static_cast<double>(j) + 0.5) * g.h,
                                           (static_cast<double>(k) + 0.5) * g.h});
          Vec3 local[3] = {sub(tri[0], centre), sub(tri[1], centre), sub(tri[2], centre)};
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
        Vec3 centre = add(g.origin, Vec3{(static_cast<double>(i) + 0.5) * g.h,
                                         (static_cast<double>(j) + 0.5) * g.h,
                                         (static_cast<double>(k) + 0.5) * g.h});
        if (std::abs(winding_number(s, centre)) > 0.5) {
          for (int64_t r = i; r < end; ++r) active[static_cast<size_t>(g.cell(r, j, k))] = 1;
        }
        i = end;
      }
    }
  }
}

// Majority rule for the cells the surface cuts: keep a cell when at least 5 of 9 samples (its
// centre and its 8 corners, corners cached since neighbours share them) are inside.
void keep_majority_cells(const SurfaceMesh& s, const Grid& g, const std::vector<char>& touched,
                         std::vector<char>& active) {
  const int64_t nodes_x = g.n[0] + 1, nodes_y = g.n[1] + 1;
  std::vector<signed char> node_inside(static_cast<size_t>(nodes_x * nodes_y * (g.n[2] + 1)),
                                       -1);  // -1: not yet known
  auto inside = [&](const Vec3& p) { return std::abs(winding_number(s, p)) > 0.5; };
  for (int64_t k = 0; k < g.n[2]; ++k) {
    for (int64_t j = 0; j < g.n[1]; ++j) {
      for (int64_t i = 0; i < g.n[0]; ++i) {
        const auto c = static_cast<size_t>(g.cell(i, j, k));
        if (!touched[c]) continue;
        Vec3 base = add(g.origin, Vec3{static_cast<double>(i) * g.h, static_cast<double>(j) * g.h,
                                       static_cast<double>(k) * g.h});
        int votes = inside(add(base, Vec3{0.5 * g.h, 0.5 * g.h, 0.5 * g.h})) ? 1 : 0;
        for (int64_t corner = 0; corner < 8; ++corner) {
          int64_t di = corner & 1, dj = (corner >> 1) & 1, dk = (corner >> 2) & 1;
          signed char& known = node_inside[static_cast<size_t>(
              (i + di) + nodes_x * ((j + dj) + nodes_y * (k + dk)))];
          if (known < 0) {
            known =
                inside(add(base, Vec3{static_cast<double>(di) * g.h, static_cast<double>(dj) * g.h,
                                      static_cast<double>(dk) * g.h}))
                    ? 1
                    : 0;
          }
          votes += known;
        }
        active[c] = votes >= 5 ? 1 : 0;
      }
    }
  }
}

// The kept cell nearest to cell (i, j, k): rings of growing Chebyshev radius, nearest centre first;
// one more ring is searched after the first hit, since a cell of it can still be nearer.
int64_t nearest_kept_cell(const Grid& g, const std::vector<uint32_t>& first_tet,
                          const int64_t at[3]) {
  int64_t best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  int64_t found_radius = -1;
  const int64_t max_radius = std::max({g.n[0], g.n[1], g.n[2]});
  for (int64_t r = 1; r <= max_radius && (found_radius < 0 || r <= found_radius + 1); ++r) {
    for (int64_t k = std::max<int64_t>(0, at[2] - r); k <= std::min(g.n[2] - 1, at[2] + r); ++k) {
      for (int64_t j = std::max<int64_t>(0, at[1] - r); j <= std::min(g.n[1] - 1, at[1] + r); ++j) {
        for (int64_t i = std::max<int64_t>(0, at[0] - r); i <= std::min(g.n[0] - 1, at[0] + r);
             ++i) {
          if (std::max({std::abs(i - at[0]), std::abs(j - at[1]), std::abs(k - at[2])}) != r)
            continue;  // ring only
          if (first_tet[static_cast<size_t>(g.cell(i, j, k))] == UINT32_MAX) continue;
          double d = std::hypot(static_cast<double>(i - at[0]), static_cast<double>(j - at[1]),
                                static_cast<double>(k - at[2]));
          if (d < best_distance) {
            best_distance = d;
            best = g.cell(i, j, k);
            if (found_radius < 0) found_radius = r;
          }
        }
      }
    }
  }
  return best;
}

// Connected pieces of the surface: triangles joined through shared vertices.
size_t count_shells(const SurfaceMesh& s) {
  mesh_detail::NodeUnion shells_of(s.vertex_count());
  shells_of.join_elements(s.triangles, 3);
  std::vector<char> is_root(s.vertex_count(), 0);
  size_t shells = 0;
  for (uint32_t v : s.triangles)
    if (!is_root[shells_of.root(v)]) {
      is_root[shells_of.root(v)] = 1;
      ++shells;
    }
  return shells;
}

// Cells per face-connected piece of the kept cells (tets of cells that meet only at an edge or a
// corner hinge there: counted apart), largest first.
std::vector<size_t> piece_sizes(const Grid& g, const std::vector<char>& active) {
  std::vector<char> seen(active.size(), 0);
  std::vector<int64_t> stack;
  std::vector<size_t> sizes;
  for (int64_t start = 0; start < static_cast<int64_t>(active.size()); ++start) {
    if (!active[static_cast<size_t>(start)] || seen[static_cast<size_t>(start)]) continue;
    size_t count = 0;
    stack.assign(1, start);
    seen[static_cast<size_t>(start)] = 1;
    while (!stack.empty()) {
      const int64_t c = stack.back();
      stack.pop_back();
      ++count;
      const int64_t at[3] = {c % g.n[0], (c / g.n[0]) % g.n[1], c / (g.n[0] * g.n[1])};
      for (int axis = 0; axis < 3; ++axis)
        for (int64_t step : {-1, 1}) {
          int64_t next[3] = {at[0], at[1], at[2]};
          next[axis] += step;
          if (next[axis] < 0 || next[axis] >= g.n[axis]) continue;
          const auto n = static_cast<size_t>(g.cell(next[0], next[1], next[2]));
          if (active[n] && !seen[n]) {
            seen[n] = 1;
            stack.push_back(static_cast<int64_t>(n));
          }
        }
    }
    sizes.push_back(count);
  }
  std::sort(sizes.rbegin(), sizes.rend());
  return sizes;
}

std::string volumes_text(const std::vector<double>& volumes) {
  std::string text;
  for (size_t i = 0; i < volumes.size() && i < 8; ++i)
    text += (i ? ", " : "") + fmt::format("{:.3g}", volumes[i]);
  if (volumes.size() > 8) text += ", ...";
  return text + " m^3";
}

// Majority can cut a shell where it is thinner than a cell (pieces that would fall apart) or drop
// a thin part: the cells the surface crosses are then kept too, which joins every shell into one
// piece (a connected surface crosses a face-connected run of cells) at the cost of some volume.
void keep_one_piece_per_shell(const SurfaceMesh& s, const Grid& g, const std::vector<char>& touched,
                              std::vector<char>& active, LoadReport& r) {
  const size_t pieces_before = piece_sizes(g, active).size();
  if (pieces_before <= r.shells) return;
  r.split_pieces = pieces_before;
  for (size_t c = 0; c < active.size(); ++c) active[c] = static_cast<char>(active[c] | touched[c]);
  const size_t pieces_after = piece_sizes(g, active).size();
  r.warnings.push_back(fmt::format(
      "the voxels inside the surface fell into {} pieces for {} surface shell(s); the cells "
      "the surface crosses were kept too, which joined them into {}",
      pieces_before, r.shells, pieces_after));
  if (pieces_after > r.shells) {
    std::vector<double> volumes;
    for (size_t cells : piece_sizes(g, active))
      volumes.push_back(static_cast<double>(cells) * g.h * g.h * g.h);
    throw InputError({s.source, 0, 0, ""},
                     fmt::format("voxel size {:.4g} m cuts the body into {} pieces ({}), more than "
                                 "its {} surface shell(s); give a smaller voxel_size",
                                 g.h, volumes.size(), volumes_text(volumes), r.shells));
  }
}

}  // namespace

VolumeMesh voxelize(const SurfaceMesh& closed, double cell_size, LoadReport* report,
                    VoxelFill fill) {
  LoadReport local;
  LoadReport& r = report ? *report : local;
  const std::string& source = closed.source;
  if (!(cell_size > 0) || !std::isfinite(cell_size))
    throw InputError({source, 0, 0, ""}, "voxel size must be positive and finite");
  if (closed.triangle_count() == 0)
    throw InputError({source, 0, 0, ""}, "cannot voxelise a surface with no triangles");
  check_closed(closed, r);
  if (!r.closed()) {
    r.warnings.push_back("the surface is not closed (" + std::to_string(r.boundary_edges) +
                         " open edges, " + std::to_string(r.nonmanifold_edges) +
                         " non-manifold edges); its inside is a best guess");
  }
  Vec3 lo{{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity()}};
  Vec3 hi = scaled(lo, -1.0);
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
    g.origin[a] =
        lo[a] - 0.5 * cell_size;  // half a cell of margin: no vertex on the grid's outer faces
    double count = std::ceil((hi[a] - lo[a]) / cell_size) + 1;
    if (!(count <= static_cast<double>(kMaxCells)))
      throw InputError({source, 0, 0, ""}, "voxel size too small for the surface");
    g.n[a] = static_cast<int64_t>(count);
    cells *= g.n[a];
    if (cells > kMaxCells) {
      throw InputError({source, 0, 0, ""}, "voxel size " + std::to_string(cell_size) +
                                               " m gives more than 2 million cells");
    }
  }
  std::vector<char> touched(static_cast<size_t>(cells), 0);
  mark_touched_cells(closed, g, touched);
  std::vector<char> active = touched;
  mark_inside_cells(closed, g, active);
  r.shells = count_shells(closed);
  r.voxel_size = g.h;
  r.enclosed_volume = std::abs(enclosed_volume(closed));
  if (fill == VoxelFill::Majority) {
    keep_majority_cells(closed, g, touched, active);
    keep_one_piece_per_shell(closed, g, touched, active, r);
  }
  if (std::find(active.begin(), active.end(), 1) == active.end()) {
    throw InputError({source, 0, 0, ""},
                     "no voxel cell is mostly inside the surface; use a smaller voxel size");
  }

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
            mesh.positions.insert(mesh.positions.end(),
                                  {g.origin[0] + static_cast<double>(ni) * g.h,
                                   g.origin[1] + static_cast<double>(nj) * g.h,
                                   g.origin[2] + static_cast<double>(nk) * g.h});
          }
          corner[c] = id;
        }
        first_tet[static_cast<size_t>(g.cell(i, j, k))] = static_cast<uint32_t>(mesh.tet_count());
        mesh_detail::append_cell_tets(corner, mesh.tets, mesh_detail::alternating_mirror(i, j, k));
      }
    }
  }

  Embedding e;
  e.surface = closed;
  e.element.resize(closed.vertex_count());
  e.weights.resize(4 * closed.vertex_count());
  size_t outside = 0;
  for (size_t v = 0; v < closed.vertex_count(); ++v) {
    Vec3 p = point(closed.positions, static_cast<uint32_t>(v));
    int64_t idx[3];
    for (int a = 0; a < 3; ++a) idx[a] = g.clamp_index(p[static_cast<size_t>(a)], a);
    int64_t cell = g.cell(idx[0], idx[1], idx[2]);
    std::array<double, 4> weights{};
    uint32_t tet = 0;
    if (first_tet[static_cast<size_t>(cell)] != UINT32_MAX) {
      // Inside its own cell: the Kuhn tet is read off the ordering of the local coordinates.
      int64_t at[3] = {idx[0], idx[1], idx[2]};
      double in_cell[3];
      for (int a = 0; a < 3; ++a) {
        in_cell[a] = (p[static_cast<size_t>(a)] - g.origin[static_cast<size_t>(a)]) / g.h -
                     static_cast<double>(at[a]);
      }
      const unsigned mirror = mesh_detail::alternating_mirror(at[0], at[1], at[2]);
      tet = first_tet[static_cast<size_t>(cell)] + static_cast<uint32_t>(mesh_detail::cell_tet_of(
                                                       in_cell[0], in_cell[1], in_cell[2], mirror));
      const uint32_t* n = &mesh.tets[4 * size_t{tet}];
      weights =
          mesh_detail::barycentric(p, point(mesh.positions, n[0]), point(mesh.positions, n[1]),
                                   point(mesh.positions, n[2]), point(mesh.positions, n[3]));
    } else {
      // Outside every kept cell: the tet of the nearest kept cell that needs the least extrapolation.
      ++outside;
      cell = nearest_kept_cell(g, first_tet, idx);
      double best = -std::numeric_limits<double>::infinity();
      for (uint32_t t = first_tet[static_cast<size_t>(cell)];
           t < first_tet[static_cast<size_t>(cell)] + 6; ++t) {
        const uint32_t* n = &mesh.tets[4 * size_t{t}];
        auto w =
            mesh_detail::barycentric(p, point(mesh.positions, n[0]), point(mesh.positions, n[1]),
                                     point(mesh.positions, n[2]), point(mesh.positions, n[3]));
        double lowest = std::min({w[0], w[1], w[2], w[3]});
        if (lowest > best) {
          best = lowest;
          tet = t;
          weights = w;
        }
      }
    }
    e.element[v] = tet;
    std::copy(weights.begin(), weights.end(),
              e.weights.begin() + static_cast<std::ptrdiff_t>(4 * v));
  }
  if (outside > 0) {
    r.warnings.push_back(
        std::to_string(outside) +
        " surface vertices lie outside the voxel tets and follow them by extrapolation");
  }
  mesh.embedding = std::move(e);
  finalize(mesh, &r);
  const double cell_volume = g.h * g.h * g.h;
  r.voxel_cells = mesh.tet_count() / 6;
  r.mesh_volume = static_cast<double>(r.voxel_cells) * cell_volume;
  if (r.enclosed_volume > 0 &&
      (r.mesh_volume < 0.8 * r.enclosed_volume || r.mesh_volume > 1.25 * r.enclosed_volume)) {
    r.warnings.push_back(fmt::format(
        "the voxels hold {:.0f}% of the volume the surface encloses; a smaller voxel_size "
        "follows it closer",
        100 * r.mesh_volume / r.enclosed_volume));
  }
  return mesh;
}

}  // namespace tacta
