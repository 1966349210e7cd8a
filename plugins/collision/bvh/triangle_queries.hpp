// Point-triangle closest point and sphere cast against one triangle, for the haptic proxy.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "tacta/vec3.hpp"

namespace tacta::collision {

// Closest point of triangle (a, b, c) to p by Voronoi regions; writes barycentric weights.
inline Vec3 closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                                std::array<double, 3>& w) {
  const Vec3 ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  auto at = [&](double u, double v) {
    w = {1.0 - u - v, u, v};
    return Vec3{a[0] + u * ab[0] + v * ac[0], a[1] + u * ab[1] + v * ac[1],
                a[2] + u * ab[2] + v * ac[2]};
  };
  if (d1 <= 0.0 && d2 <= 0.0) return at(0, 0);
  const Vec3 bp = sub(p, b);
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3) return at(1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) return at(d1 / (d1 - d3), 0);
  const Vec3 cp = sub(p, c);
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6) return at(0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) return at(0, d2 / (d2 - d6));
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return at(1.0 - t, t);
  }
  const double denom = va + vb + vc;
  // denom is |ab x ac|^2: a sliver's (angle at a under 1e-4 rad) is rounding noise, and its
  // weights from it are too.
  if (!(denom > 1e-8 * dot(ab, ab) * dot(ac, ac))) {
    // No face to speak of (corners on a line, up to rounding): the nearest point of the three
    // edges, each as (u, v) along ab, ac or from b to c.
    const auto along = [&](const Vec3& from, const Vec3& edge) {
      const double length2 = dot(edge, edge);
      return length2 > 0.0 ? std::clamp(dot(sub(p, from), edge) / length2, 0.0, 1.0) : 0.0;
    };
    const double t_ab = along(a, ab), t_ac = along(a, ac), t_bc = along(b, sub(c, b));
    const std::array<std::array<double, 2>, 3> uv{{{t_ab, 0.0}, {0.0, t_ac}, {1.0 - t_bc, t_bc}}};
    size_t nearest = 0;
    double least = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < 3; ++k) {
      const Vec3 q = at(uv[k][0], uv[k][1]);
      const double gap2 = dot(sub(p, q), sub(p, q));
      if (gap2 < least) {
        least = gap2;
        nearest = k;
      }
    }
    return at(uv[nearest][0], uv[nearest][1]);
  }
  return at(vb / denom, vc / denom);
}

inline double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  std::array<double, 3> w;
  const Vec3 q = sub(p, closest_on_triangle(p, a, b, c, w));
  return norm(q);
}

namespace detail {
// Smallest root s in [0, 1] of a s^2 + b s + c = 0 where the value falls through 0 (c > 0: the
// start is outside), or -1. Roots in the form that does not cancel.
inline double entering_root(double a, double b, double c) {
  if (!(a > 0.0) || !(c > 0.0) || b >= 0.0) return -1.0;  // not moving toward it
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return -1.0;
  const double s = 2.0 * c / (-b + std::sqrt(disc));  // = (-b - sqrt(disc)) / 2a
  return s <= 1.0 ? s : -1.0;
}
}  // namespace detail

// First fraction s in [0, 1] at which a sphere of radius r moving from -> to touches the
// triangle, or -1. The triangle is its face, three edges and three corners: the first touch of
// the whole is the earliest of the first touches of the parts, each in closed form (the plane
// offset by r, a cylinder of radius r around an edge with its foot inside the edge, a sphere of
// radius r around a corner). A start already within r touches at 0.
inline double sphere_cast_triangle(const Vec3& from, const Vec3& to, double r, const Vec3& a,
                                   const Vec3& b, const Vec3& c) {
  // Ends on one side of the triangle's plane, both further than r (and 1 pm for rounding) from
  // it: no point of the sweep comes within r. A proxy sliding over a face rejects the faces
  // around it so, for a cross product and two dots instead of two closest points. Only where
  // the plane is known: a sliver (angle at a under 1e-4 rad) has a normal of rounding noise.
  const Vec3 ab = sub(b, a), ac = sub(c, a);
  const Vec3 normal = cross(ab, ac);
  const double twice_area = norm(normal);
  if (twice_area > 1e-4 * norm(ab) * norm(ac)) {
    const double h0 = dot(sub(from, a), normal) / twice_area;
    const double h1 = dot(sub(to, a), normal) / twice_area;
    if ((h0 - r > 1e-12 && h1 - r > 1e-12) || (-h0 - r > 1e-12 && -h1 - r > 1e-12)) return -1.0;
  }
  if (distance_to_triangle(from, a, b, c) <= r) return 0.0;
  const Vec3 d = sub(to, from);
  // Every point of the sweep is within half its length of its middle: a triangle further than
  // that (and r, and 1 pm for rounding) from the middle is never touched. Most candidates a box
  // query hands over end here.
  const Vec3 middle = add_scaled(from, d, 0.5);
  if (distance_to_triangle(middle, a, b, c) - 0.5 * norm(d) - r > 1e-12) return -1.0;
  double first = 2.0;
  // Face: the centre reaches the plane offset by r on its own side, over the triangle.
  if (twice_area > 0.0) {
    const Vec3 n = scaled(normal, 1.0 / twice_area);
    const double height = dot(sub(from, a), n), closing = dot(d, n);
    const double side = height >= 0.0 ? 1.0 : -1.0;
    if (std::abs(height) > r && side * closing < 0.0) {
      const double s = (std::abs(height) - r) / (-side * closing);
      // Where the centre is then, over the plane: inside when on the inner side of each edge.
      const Vec3 centre = add_scaled(from, d, s);
      if (s <= 1.0 && dot(cross(sub(b, a), sub(centre, a)), normal) >= 0.0 &&
          dot(cross(sub(c, b), sub(centre, b)), normal) >= 0.0 &&
          dot(cross(sub(a, c), sub(centre, c)), normal) >= 0.0)
        first = s;
    }
  }
  // Edges: the centre reaches the cylinder of radius r around the edge's line, its foot inside.
  const Vec3* corner[3] = {&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Vec3& p = *corner[k];
    const Vec3 e = sub(*corner[(k + 1) % 3], p);
    const double length2 = dot(e, e);
    if (!(length2 > 0.0)) continue;
    const Vec3 m = sub(from, p);
    const Vec3 m_off = add_scaled(m, e, -dot(m, e) / length2);  // parts across the edge
    const Vec3 d_off = add_scaled(d, e, -dot(d, e) / length2);
    const double s = detail::entering_root(dot(d_off, d_off), 2.0 * dot(m_off, d_off),
                                           dot(m_off, m_off) - r * r);
    if (s < 0.0 || s >= first) continue;
    const double t = dot(add_scaled(m, d, s), e) / length2;
    if (t >= 0.0 && t <= 1.0) first = s;
  }
  // Corners.
  for (const Vec3* v : corner) {
    const Vec3 m = sub(from, *v);
    const double s = detail::entering_root(dot(d, d), 2.0 * dot(m, d), dot(m, m) - r * r);
    if (s >= 0.0 && s < first) first = s;
  }
  return first <= 1.0 ? first : -1.0;
}

}  // namespace tacta::collision
