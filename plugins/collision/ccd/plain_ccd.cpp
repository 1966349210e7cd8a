// Plain Moore-Wilhelms: cubic roots by monotone-interval bisection, then an inside test.
#include "plain_ccd.hpp"

#include <array>
#include <cmath>

#include "tacta/vec3.hpp"

namespace tacta::collision {
namespace {

using Vec = std::array<double, 3>;

Vec lerp(const double* p, int index, double t) {
  const Vec a = point_at(p, index), b = point_at(p, index + 4);
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}
double det(const Vec& a, const Vec& b, const Vec& c) { return triple(a, b, c); }

// det(A0 + t A1, B0 + t B1, C0 + t C1) = c[0] + c[1] t + c[2] t^2 + c[3] t^3.
std::array<double, 4> cubic(const Vec& a0, const Vec& a1, const Vec& b0, const Vec& b1,
                            const Vec& c0, const Vec& c1) {
  return {det(a0, b0, c0), det(a1, b0, c0) + det(a0, b1, c0) + det(a0, b0, c1),
          det(a1, b1, c0) + det(a1, b0, c1) + det(a0, b1, c1), det(a1, b1, c1)};
}

double value(const std::array<double, 4>& c, double t) {
  return ((c[3] * t + c[2]) * t + c[1]) * t + c[0];
}

// Real roots in [0, 1], increasing; count returned. The cubic is split at the roots of its
// derivative into monotone pieces, each bisected where it changes sign.
int roots_in_unit(const std::array<double, 4>& c, std::array<double, 3>& roots) {
  std::array<double, 4> cuts{0.0, 1.0, 1.0, 1.0};
  int cut_count = 1;
  const double qa = 3.0 * c[3], qb = 2.0 * c[2], qc = c[1];
  std::array<double, 2> critical{};
  int critical_count = 0;
  if (qa != 0.0) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc >= 0.0) {
      const double r = std::sqrt(disc);
      critical = {(-qb - r) / (2.0 * qa), (-qb + r) / (2.0 * qa)};
      if (critical[0] > critical[1]) std::swap(critical[0], critical[1]);
      critical_count = 2;
    }
  } else if (qb != 0.0) {
    critical[0] = -qc / qb;
    critical_count = 1;
  }
  for (int i = 0; i < critical_count; ++i)
    if (critical[i] > 0.0 && critical[i] < 1.0) cuts[cut_count++] = critical[i];
  cuts[cut_count++] = 1.0;
  int count = 0;
  for (int i = 0; i + 1 < cut_count; ++i) {
    double lo = cuts[i], hi = cuts[i + 1];
    double flo = value(c, lo), fhi = value(c, hi);
    if (flo == 0.0) {
      if (count == 0 || roots[count - 1] != lo) roots[count++] = lo;
      continue;
    }
    if (fhi == 0.0 || (flo < 0.0) == (fhi < 0.0)) {
      if (fhi == 0.0 && i + 2 == cut_count) roots[count++] = hi;
      continue;
    }
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      const double fm = value(c, mid);
      if ((fm < 0.0) == (flo < 0.0)) {
        lo = mid;
        flo = fm;
      } else {
        hi = mid;
      }
    }
    roots[count++] = 0.5 * (lo + hi);
    if (count == 3) break;
  }
  return count;
}

}  // namespace

CcdResult vertex_face_plain(const double* p) noexcept {
  CcdResult result;
  const Vec e1a = sub(point_at(p, 2), point_at(p, 1)), e2a = sub(point_at(p, 3), point_at(p, 1));
  const Vec wa = sub(point_at(p, 0), point_at(p, 1));
  const Vec e1b = sub(point_at(p, 6), point_at(p, 5)), e2b = sub(point_at(p, 7), point_at(p, 5));
  const Vec wb = sub(point_at(p, 4), point_at(p, 5));
  const std::array<double, 4> c = cubic(e1a, sub(e1b, e1a), e2a, sub(e2b, e2a), wa, sub(wb, wa));
  std::array<double, 3> roots{};
  const int count = roots_in_unit(c, roots);
  for (int i = 0; i < count; ++i) {
    const double t = roots[i];
    const Vec f0 = lerp(p, 1, t), e1 = sub(lerp(p, 2, t), f0), e2 = sub(lerp(p, 3, t), f0);
    const Vec w = sub(lerp(p, 0, t), f0);
    // Barycentric coordinates from the 2x2 normal equations of the triangle's plane.
    const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2);
    const double d1w = dot(e1, w), d2w = dot(e2, w);
    const double denominator = d11 * d22 - d12 * d12;
    if (denominator == 0.0) continue;
    const double u = (d22 * d1w - d12 * d2w) / denominator;
    const double v = (d11 * d2w - d12 * d1w) / denominator;
    if (u >= 0.0 && v >= 0.0 && u + v <= 1.0) {
      result.hit = true;
      result.toi = t;
      result.u = u;
      result.v = v;
      return result;
    }
  }
  return result;
}

CcdResult edge_edge_plain(const double* p) noexcept {
  CcdResult result;
  const Vec ea = sub(point_at(p, 1), point_at(p, 0)), eb = sub(point_at(p, 3), point_at(p, 2));
  const Vec wa = sub(point_at(p, 2), point_at(p, 0));
  const Vec ea1 = sub(point_at(p, 5), point_at(p, 4)), eb1 = sub(point_at(p, 7), point_at(p, 6));
  const Vec wa1 = sub(point_at(p, 6), point_at(p, 4));
  const std::array<double, 4> c = cubic(ea, sub(ea1, ea), eb, sub(eb1, eb), wa, sub(wa1, wa));
  std::array<double, 3> roots{};
  const int count = roots_in_unit(c, roots);
  for (int i = 0; i < count; ++i) {
    const double t = roots[i];
    const Vec a0 = lerp(p, 0, t), a = sub(lerp(p, 1, t), a0);
    const Vec b0 = lerp(p, 2, t), b = sub(lerp(p, 3, t), b0);
    const Vec w = sub(b0, a0);
    // Line parameters of the closest points; parallel lines have none.
    const double aa = dot(a, a), ab = dot(a, b), bb = dot(b, b), aw = dot(a, w), bw = dot(b, w);
    const double denominator = aa * bb - ab * ab;
    if (denominator == 0.0) continue;
    const double s = (aw * bb - ab * bw) / denominator;
    const double r = (ab * aw - aa * bw) / denominator;
    if (s >= 0.0 && s <= 1.0 && r >= 0.0 && r <= 1.0) {
      result.hit = true;
      result.toi = t;
      result.u = s;
      result.v = r;
      return result;
    }
  }
  return result;
}

}  // namespace tacta::collision
