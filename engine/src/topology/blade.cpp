#include "topology/blade.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tacta::topology_detail {

namespace {

constexpr double kRoundOff = 1e-12;  // relative: of a length, of an area, of a projection

}  // namespace

bool Box::meets(const Box& other, double pad) const noexcept {
  for (size_t a = 0; a < 3; ++a)
    if (lo[a] > other.hi[a] + pad || other.lo[a] > hi[a] + pad) return false;
  return true;
}

void Box::include(const Vec3& p) noexcept {
  for (size_t a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
}

Box Box::empty() noexcept {
  constexpr double inf = std::numeric_limits<double>::infinity();
  return {{inf, inf, inf}, {-inf, -inf, -inf}};
}

std::vector<BladeTriangle> cutting_triangles(std::span<const double> triangles) {
  std::vector<BladeTriangle> out;
  for (size_t t = 0; t + 9 <= triangles.size(); t += 9) {
    BladeTriangle tri{point_at(&triangles[t], 0), point_at(&triangles[t], 1),
                      point_at(&triangles[t], 2), Box::empty()};
    if (!is_finite(tri.a) || !is_finite(tri.b) || !is_finite(tri.c)) continue;
    const double longest =
        std::max({distance(tri.a, tri.b), distance(tri.b, tri.c), distance(tri.c, tri.a)});
    if (!(norm(cross(sub(tri.b, tri.a), sub(tri.c, tri.a))) > kRoundOff * longest * longest))
      continue;
    for (const Vec3& p : {tri.a, tri.b, tri.c}) tri.box.include(p);
    out.push_back(tri);
  }
  return out;
}

bool triangle_meets_tet_interior(const BladeTriangle& triangle, const std::array<Vec3, 4>& x) {
  // Everything relative to the tet's first node, so projections are of lengths near its size.
  const Vec3 t[4] = {{0, 0, 0}, sub(x[1], x[0]), sub(x[2], x[0]), sub(x[3], x[0])};
  const Vec3 s[3] = {sub(triangle.a, x[0]), sub(triangle.b, x[0]), sub(triangle.c, x[0])};
  static constexpr int kEdges[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  Vec3 tet_edges[6];
  double size = 0;
  for (size_t e = 0; e < 6; ++e) {
    tet_edges[e] = sub(t[kEdges[e][1]], t[kEdges[e][0]]);
    size = std::max(size, norm(tet_edges[e]));
  }
  const Vec3 tri_edges[3] = {sub(s[1], s[0]), sub(s[2], s[1]), sub(s[0], s[2])};
  // An axis along which the two project to intervals that overlap by round-off at most.
  auto separates = [&](const Vec3& axis, double scale) {
    const double length = norm(axis);
    if (!(length > kRoundOff * scale)) return false;  // parallel edges: no direction
    double tet_lo = 0, tet_hi = 0;
    for (size_t k = 1; k < 4; ++k) {
      const double d = dot(axis, t[k]);
      tet_lo = std::min(tet_lo, d), tet_hi = std::max(tet_hi, d);
    }
    double tri_lo = dot(axis, s[0]), tri_hi = tri_lo;
    for (size_t k = 1; k < 3; ++k) {
      const double d = dot(axis, s[k]);
      tri_lo = std::min(tri_lo, d), tri_hi = std::max(tri_hi, d);
    }
    const double tolerance = kRoundOff * size * length;
    return tri_hi <= tet_lo + tolerance || tet_hi <= tri_lo + tolerance;
  };
  const double tet_scale = size * size;
  // The tet's face normals, from two edges of each face.
  if (separates(cross(tet_edges[0], tet_edges[1]), tet_scale) ||
      separates(cross(tet_edges[0], tet_edges[2]), tet_scale) ||
      separates(cross(tet_edges[1], tet_edges[2]), tet_scale) ||
      separates(cross(tet_edges[3], tet_edges[4]), tet_scale))
    return false;
  const double tri_size = std::max({norm(tri_edges[0]), norm(tri_edges[1]), norm(tri_edges[2])});
  if (separates(cross(tri_edges[0], tri_edges[1]), tri_size * tri_size)) return false;
  for (const Vec3& e : tet_edges)
    for (const Vec3& f : tri_edges)
      if (separates(cross(e, f), norm(e) * norm(f))) return false;
  return true;
}

bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const BladeTriangle& triangle) {
  const Vec3& a = triangle.a;
  const Vec3 normal = cross(sub(triangle.b, a), sub(triangle.c, a));
  if ((dot(normal, sub(p, a)) > 0) == (dot(normal, sub(q, a)) > 0)) return false;
  // The line p-q against each edge: all signed volumes of one sign (zeros allowed) when it
  // passes through the closed triangle.
  const Vec3 d = sub(q, p);
  const double u = triple(d, sub(a, p), sub(triangle.b, p));
  const double v = triple(d, sub(triangle.b, p), sub(triangle.c, p));
  const double w = triple(d, sub(triangle.c, p), sub(a, p));
  const bool below = u < 0 || v < 0 || w<0, above = u> 0 || v > 0 || w > 0;
  return below != above;
}

}  // namespace tacta::topology_detail
