// Point-triangle closest point and sphere cast against one triangle, for the haptic proxy.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

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
  if (!(denom > 0.0)) return at(0, 0);  // degenerate triangle: fall back to a corner
  return at(vb / denom, vc / denom);
}

inline double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  std::array<double, 3> w;
  const Vec3 q = sub(p, closest_on_triangle(p, a, b, c, w));
  return norm(q);
}

// First fraction s in [0, 1] at which a sphere of radius r moving from -> to touches the
// triangle, or -1. The distance from a linearly moving point to a convex set is convex in s,
// so: touching at 0, else find the minimum by golden search and bisect the decreasing part.
inline double sphere_cast_triangle(const Vec3& from, const Vec3& to, double r, const Vec3& a,
                                   const Vec3& b, const Vec3& c) {
  auto gap = [&](double s) {
    const Vec3 p{from[0] + s * (to[0] - from[0]), from[1] + s * (to[1] - from[1]),
                 from[2] + s * (to[2] - from[2])};
    return distance_to_triangle(p, a, b, c) - r;
  };
  if (gap(0.0) <= 0.0) return 0.0;
  // Every point of the sweep is within half its length of its middle: a triangle further than
  // that (and r, and 1 pm for rounding) from the middle is never touched, and most candidates a
  // box query hands over are rejected here before the search.
  const Vec3 middle{0.5 * (from[0] + to[0]), 0.5 * (from[1] + to[1]), 0.5 * (from[2] + to[2])};
  if (distance_to_triangle(middle, a, b, c) - 0.5 * norm(sub(to, from)) - r > 1e-12) return -1.0;
  double lo = 0.0, hi = 1.0;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < 60 && hi - lo > 1e-12; ++i) {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (gap(m1) < gap(m2))
      hi = m2;
    else
      lo = m1;
  }
  double s_min = 0.5 * (lo + hi);
  if (gap(1.0) < gap(s_min)) s_min = 1.0;
  if (gap(s_min) > 0.0) return -1.0;
  lo = 0.0;
  hi = s_min;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (gap(mid) > 0.0)
      lo = mid;
    else
      hi = mid;
  }
  return hi;
}

}  // namespace tacta::collision
