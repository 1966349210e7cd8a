#include "tacta/embedded_surface.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include "mesh/geometry.hpp"
#include "tacta/error.hpp"
#include "tacta/vec3.hpp"

namespace tacta {

namespace {

using mesh_detail::point;

struct Box {
  Vec3 lo, hi;
  // Distance (m) from p to the box, 0 inside.
  double distance(const Vec3& p) const {
    double d2 = 0;
    for (size_t a = 0; a < 3; ++a) {
      const double out = std::max({lo[a] - p[a], 0.0, p[a] - hi[a]});
      d2 += out * out;
    }
    return std::sqrt(d2);
  }
};

std::array<double, 4> weights_in(const VolumeMesh& mesh, size_t t, const Vec3& p) {
  const uint32_t* n = &mesh.tets[4 * t];
  return mesh_detail::barycentric(p, point(mesh.positions, n[0]), point(mesh.positions, n[1]),
                                  point(mesh.positions, n[2]), point(mesh.positions, n[3]));
}

double lowest(const double* w) { return std::min({w[0], w[1], w[2], w[3]}); }
double lowest(const std::array<double, 4>& w) { return lowest(w.data()); }

// Tets bucketed by the grid cells their boxes overlap (cells at least a mean tet wide, at most
// 128 a side), so that binding a vertex looks at the tets near it, not at all of them.
class TetGrid {
 public:
  TetGrid(const std::vector<Box>& boxes, double mean_diagonal) {
    Box all = boxes[0];
    for (const Box& b : boxes)
      for (size_t a = 0; a < 3; ++a)
        all.lo[a] = std::min(all.lo[a], b.lo[a]), all.hi[a] = std::max(all.hi[a], b.hi[a]);
    origin_ = all.lo;
    const double extent =
        std::max({all.hi[0] - all.lo[0], all.hi[1] - all.lo[1], all.hi[2] - all.lo[2]});
    h_ = std::max({mean_diagonal, extent / 128.0, 1e-300});
    for (size_t a = 0; a < 3; ++a) n_[a] = static_cast<int64_t>((all.hi[a] - all.lo[a]) / h_) + 1;
    start_.assign(static_cast<size_t>(n_[0] * n_[1] * n_[2]) + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {  // count, then fill
      std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
      for (size_t t = 0; t < boxes.size(); ++t) {
        int64_t lo[3], hi[3];
        for (size_t a = 0; a < 3; ++a)
          lo[a] = index(boxes[t].lo[a], a), hi[a] = index(boxes[t].hi[a], a);
        for (int64_t k = lo[2]; k <= hi[2]; ++k)
          for (int64_t j = lo[1]; j <= hi[1]; ++j)
            for (int64_t i = lo[0]; i <= hi[0]; ++i) {
              const size_t c = cell(i, j, k);
              if (pass == 0)
                ++start_[c + 1];
              else
                items_[fill[c]++] = static_cast<uint32_t>(t);
            }
      }
      if (pass == 0) {
        for (size_t c = 1; c < start_.size(); ++c) start_[c] += start_[c - 1];
        items_.resize(start_.back());
      }
    }
  }
  double cell_size() const { return h_; }
  // Visits the tets listed in the cells at Chebyshev distance r from p's cell (a tet may come
  // more than once); false when no cell of the grid is that far.
  template <class Visit>
  bool ring(const Vec3& p, int64_t r, Visit&& visit) const {
    int64_t c[3], lo[3], hi[3];
    bool any = false;
    for (size_t a = 0; a < 3; ++a) {
      c[a] = index(p[a], a);
      lo[a] = std::max<int64_t>(c[a] - r, 0);
      hi[a] = std::min<int64_t>(c[a] + r, n_[a] - 1);
      any = any || c[a] - r >= 0 || c[a] + r < n_[a];
    }
    if (!any) return false;
    auto visit_cell = [&](int64_t i, int64_t j, int64_t k) {
      const size_t at = cell(i, j, k);
      for (uint32_t q = start_[at]; q < start_[at + 1]; ++q) visit(items_[q]);
    };
    for (int64_t i = lo[0]; i <= hi[0]; ++i)
      for (int64_t j = lo[1]; j <= hi[1]; ++j) {
        if (r == 0 || std::abs(i - c[0]) == r || std::abs(j - c[1]) == r) {
          for (int64_t k = lo[2]; k <= hi[2]; ++k) visit_cell(i, j, k);
          continue;
        }
        // Inside the ring's x-y rim: only its top and bottom cells.
        if (c[2] - r >= 0) visit_cell(i, j, c[2] - r);
        if (c[2] + r < n_[2]) visit_cell(i, j, c[2] + r);
      }
    return true;
  }

 private:
  int64_t index(double x, size_t a) const {
    const double f = std::floor((x - origin_[a]) / h_);
    return std::clamp<int64_t>(
        std::isfinite(f) ? static_cast<int64_t>(std::clamp(f, -1.0, 1e9)) : 0, 0, n_[a] - 1);
  }
  size_t cell(int64_t i, int64_t j, int64_t k) const {
    return static_cast<size_t>(i + n_[0] * (j + n_[1] * k));
  }
  Vec3 origin_{};
  double h_ = 1;
  int64_t n_[3] = {1, 1, 1};
  std::vector<uint32_t> start_, items_;  // cell c holds items_[start_[c] .. start_[c + 1])
};

}  // namespace

Embedding bind_surface_to_tets(const SurfaceMesh& surface, const VolumeMesh& mesh,
                               LoadReport* report) {
  const size_t tets = mesh.tet_count();
  if (tets == 0)
    throw InputError({surface.source, 0, 0, ""},
                     "a surface can only be embedded in a mesh with tetrahedra");
  std::vector<Box> boxes(tets);
  double mean_diagonal = 0;
  for (size_t t = 0; t < tets; ++t) {
    Box& b = boxes[t];
    b.lo = b.hi = point(mesh.positions, mesh.tets[4 * t]);
    for (size_t k = 1; k < 4; ++k) {
      const Vec3 q = point(mesh.positions, mesh.tets[4 * t + k]);
      for (size_t a = 0; a < 3; ++a)
        b.lo[a] = std::min(b.lo[a], q[a]), b.hi[a] = std::max(b.hi[a], q[a]);
    }
    mean_diagonal += norm(sub(b.hi, b.lo)) / static_cast<double>(tets);
  }
  const size_t count = surface.vertex_count();
  Embedding e{surface, std::vector<uint32_t>(count), std::vector<double>(4 * count)};
  size_t outside = 0;
  const TetGrid grid(boxes, mean_diagonal);
  std::vector<size_t> seen(tets, SIZE_MAX);       // the vertex that last looked at each tet
  std::vector<std::pair<uint32_t, double>> near;  // tet, distance from its box (m)
  for (size_t v = 0; v < count; ++v) {
    const Vec3 p = point(surface.positions, static_cast<uint32_t>(v));
    // Tets whose box holds p; failing those (p outside the mesh), the tets whose boxes lie within
    // one mean tet size of the nearest box. Among them, the one needing the least extrapolation.
    // After ring r of the grid every box nearer than r cells has been seen.
    near.clear();
    double nearest = std::numeric_limits<double>::infinity();
    for (int64_t r = 0;; ++r) {
      const bool inside_grid = grid.ring(p, r, [&](uint32_t t) {
        if (seen[t] == v) return;
        seen[t] = v;
        near.emplace_back(t, boxes[t].distance(p));
        nearest = std::min(nearest, near.back().second);
      });
      const double reach = nearest > 0 ? nearest + mean_diagonal : 0.0;
      if (!inside_grid || (!near.empty() && static_cast<double>(r) * grid.cell_size() > reach))
        break;
    }
    const double reach = nearest > 0 ? nearest + mean_diagonal : 0.0;
    double best = -std::numeric_limits<double>::infinity();
    std::array<double, 4> best_weights{};
    uint32_t best_tet = 0;
    for (const auto& [t, distance] : near) {
      if (distance > reach) continue;
      const std::array<double, 4> w = weights_in(mesh, t, p);
      if (lowest(w) > best) best = lowest(w), best_weights = w, best_tet = t;
    }
    if (best < mesh_detail::kInsideWeight) ++outside;
    e.element[v] = best_tet;
    std::copy(best_weights.begin(), best_weights.end(),
              e.weights.begin() + static_cast<std::ptrdiff_t>(4 * v));
  }
  if (outside > 0 && report != nullptr)
    report->warnings.push_back(
        std::to_string(outside) +
        " vertices lie outside the tets and follow the nearest one by extrapolation");
  return e;
}

EmbeddedSurface make_embedded_surface(const VolumeMesh& mesh) {
  if (!mesh.embedding)
    throw InputError({mesh.source, 0, 0, ""}, "the mesh carries no embedded surface");
  const Embedding& e = *mesh.embedding;
  const size_t count = e.surface.vertex_count();
  if (e.element.size() != count || e.weights.size() != 4 * count)
    throw InputError({e.surface.source, 0, 0, ""},
                     "embedded surface: one tet and 4 weights are needed per vertex");
  EmbeddedSurface s;
  s.triangles = e.surface.triangles;
  s.corner_uvs = e.surface.corner_uvs;
  s.rest_positions = e.surface.positions;
  s.tet = e.element;
  s.weights = e.weights;
  s.source = e.surface.source;
  s.nodes.resize(4 * count);
  for (size_t v = 0; v < count; ++v) {
    if (s.tet[v] >= mesh.tet_count())
      throw InputError({s.source, 0, 0, ""}, "embedded surface vertex " + std::to_string(v) +
                                                 " names tet " + std::to_string(s.tet[v]) +
                                                 " past the mesh's " +
                                                 std::to_string(mesh.tet_count()));
    for (size_t k = 0; k < 4; ++k) s.nodes[4 * v + k] = mesh.tets[4 * size_t{s.tet[v]} + k];
    if (lowest(&s.weights[4 * v]) < mesh_detail::kInsideWeight) ++s.extrapolated_vertices;
  }
  for (uint32_t i : s.triangles)
    if (i >= count)
      throw InputError({s.source, 0, 0, ""}, "embedded surface triangle index past its vertices");
  s.positions.resize(3 * count);
  s.normals.resize(3 * count);
  update_embedded_surface(s, mesh.positions.data());
  return s;
}

void interpolate_to_surface(const EmbeddedSurface& s, const double* node_values,
                            double* out) noexcept {
  const size_t count = s.vertex_count();
  for (size_t v = 0; v < count; ++v) interpolate_vertex(s, v, node_values, out + 3 * v);
}

void update_embedded_surface(EmbeddedSurface& s, const double* node_positions) noexcept {
  interpolate_to_surface(s, node_positions, s.positions.data());
  std::fill(s.normals.begin(), s.normals.end(), 0.0);
  const double* x = s.positions.data();
  for (size_t t = 0; t < s.triangle_count(); ++t) {
    const uint32_t* i = &s.triangles[3 * t];
    const double e1[3] = {x[3 * i[1]] - x[3 * i[0]], x[3 * i[1] + 1] - x[3 * i[0] + 1],
                          x[3 * i[1] + 2] - x[3 * i[0] + 2]};
    const double e2[3] = {x[3 * i[2]] - x[3 * i[0]], x[3 * i[2] + 1] - x[3 * i[0] + 1],
                          x[3 * i[2] + 2] - x[3 * i[0] + 2]};
    // Twice the area times the unit normal: larger faces weigh more.
    const double face[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                            e1[0] * e2[1] - e1[1] * e2[0]};
    for (size_t k = 0; k < 3; ++k)
      for (size_t a = 0; a < 3; ++a) s.normals[3 * i[k] + a] += face[a];
  }
  for (size_t v = 0; v < s.vertex_count(); ++v) {
    double* n = &s.normals[3 * v];
    const double length = norm(n);
    if (length > 0) n[0] /= length, n[1] /= length, n[2] /= length;
  }
}

void spread_to_nodes(const EmbeddedSurface& s, uint32_t vertex, const double* force,
                     double* node_forces) noexcept {
  const uint32_t* n = &s.nodes[4 * size_t{vertex}];
  const double* w = &s.weights[4 * size_t{vertex}];
  for (size_t k = 0; k < 4; ++k)
    for (size_t a = 0; a < 3; ++a) node_forces[3 * n[k] + a] += w[k] * force[a];
}

std::array<double, 3> surface_point(const EmbeddedSurface& s, uint32_t triangle, const double* b,
                                    const double* node_positions) noexcept {
  const double sum = b[0] + b[1] + b[2];
  const double third = 1.0 / 3.0;
  const double bt[3] = {sum > 0 ? b[0] / sum : third, sum > 0 ? b[1] / sum : third,
                        sum > 0 ? b[2] / sum : third};
  std::array<double, 3> p{0, 0, 0};
  for (size_t k = 0; k < 3; ++k) {
    const size_t v = s.triangles[3 * size_t{triangle} + k];
    for (size_t j = 0; j < 4; ++j) {
      const double w = bt[k] * s.weights[4 * v + j];
      for (size_t a = 0; a < 3; ++a) p[a] += w * node_positions[3 * s.nodes[4 * v + j] + a];
    }
  }
  return p;
}

}  // namespace tacta
