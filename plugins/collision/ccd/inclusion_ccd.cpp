// Inclusion-based CCD: bisection over (t, u, v) with rigorous floating-point bounds.
//
// Error bound derivation (per axis; M = max |coordinate| of the 8 input points on it; u = 2^-53;
// t, s, w in [0, 1] exact):
//   d = x1 - x0                |d| <= 2M        error <= 2uM
//   t*d                                           error <= 2uM + 2uM = 4uM
//   x(t) = x0 + t*d            |x(t)| <= M      error <= 4uM + uM(1 + 4u)  ~ 5uM
//   e = y(t) - x(t)            |e| <= 2M        error <= 10uM + 2uM = 12uM
//   s*e                                           error <= 12uM + 2uM = 14uM
//   vertex-face: w - s e1 - t e2 with |w|, |e1|, |e2| <= 2M: error <= 12 + 14 + 14 + 4 + 6 = 50uM
//   edge-edge:   x_a(t) + s e_a - x_b(t) - w e_b: error <= 5 + 14 + 5 + 14 + 2 + 4 + 6 = 50uM
// Higher-order terms are below 1e-14 uM. The code widens by 128uM.
#include "inclusion_ccd.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "tacta/vec3.hpp"

namespace tacta::collision {
namespace {

enum class Kind { kVertexFace, kEdgeEdge };

struct Box {
  double t0, t1, u0, u1, v0, v1;
  uint32_t depth;
};

// Min-heap order on start time; among equal start times the deeper box first, so a sheet of
// roots (coplanar sliding) is refined depth-first instead of breadth-first.
struct LaterBox {
  bool operator()(const Box& a, const Box& b) const noexcept {
    if (a.t0 != b.t0) return a.t0 > b.t0;
    return a.depth < b.depth;
  }
};

constexpr double kUnitRoundoff = 0x1p-53;
constexpr double kErrorFactor = 128.0 * kUnitRoundoff;
constexpr uint32_t kHeapCapacity = 1024;
constexpr uint32_t kMaxDepth = 48;  // keeps every corner parameter an exact dyadic double

// Position of input point `index` (0..3) at time t, one axis.
inline double at_time(const double* p, int index, int axis, double t) noexcept {
  const double x0 = p[3 * index + axis];
  const double x1 = p[3 * (index + 4) + axis];
  return x0 + t * (x1 - x0);
}

template <Kind K>
inline double evaluate(const double* p, int axis, double t, double s, double w) noexcept {
  const double x0 = at_time(p, 0, axis, t);
  const double x1 = at_time(p, 1, axis, t);
  const double x2 = at_time(p, 2, axis, t);
  const double x3 = at_time(p, 3, axis, t);
  if constexpr (K == Kind::kVertexFace) {
    // vertex x0 minus the point (x1 + s (x2 - x1) + w (x3 - x1)) of the triangle.
    return (x0 - x1) - s * (x2 - x1) - w * (x3 - x1);
  } else {
    // point on edge a (x0 x1) minus point on edge b (x2 x3).
    return (x0 + s * (x1 - x0)) - (x2 + w * (x3 - x2));
  }
}

struct Image {
  bool contains_zero = true;
  double width = 0.0;                  // largest axis extent of the widened image, m
  std::array<double, 3> split_gain{};  // how much each parameter spreads the image
};

template <Kind K>
Image image_of(const double* p, const Box& box, const std::array<double, 3>& error) noexcept {
  Image image;
  const double ts[2] = {box.t0, box.t1};
  const double ss[2] = {box.u0, box.u1};
  const double ws[2] = {box.v0, box.v1};
  for (int axis = 0; axis < 3; ++axis) {
    double corner[8];
    for (int c = 0; c < 8; ++c)
      corner[c] = evaluate<K>(p, axis, ts[c & 1], ss[(c >> 1) & 1], ws[(c >> 2) & 1]);
    const auto [lo, hi] = std::minmax_element(corner, corner + 8);
    const double low = *lo - error[axis];
    const double high = *hi + error[axis];
    if (low > 0.0 || high < 0.0) {
      image.contains_zero = false;
      return image;
    }
    image.width = std::max(image.width, high - low);
    for (int c = 0; c < 8; ++c) {
      for (int dim = 0; dim < 3; ++dim) {
        const int bit = 1 << dim;
        if (c & bit) continue;
        image.split_gain[dim] =
            std::max(image.split_gain[dim], std::abs(corner[c | bit] - corner[c]));
      }
    }
  }
  return image;
}

// Point indices (of the 8: 0..3 at the start of the tick, 4..7 at its end) on each side.
constexpr int kVertexSide[] = {0, 4};
constexpr int kFaceSide[] = {1, 2, 3, 5, 6, 7};
constexpr int kEdgeASide[] = {0, 1, 4, 5};
constexpr int kEdgeBSide[] = {2, 3, 6, 7};

inline void difference(const double* p, int a, int b, double* d) noexcept {
  for (int k = 0; k < 3; ++k) d[k] = p[3 * a + k] - p[3 * b + k];
}

// Whether the two sides' swept hulls are more than `margin` apart along `direction`. Every point
// of a side during the tick (a vertex, a point of the face or an edge, linearly moving) lies in
// the convex hull of that side's start and end points, so a gap between the projections holds
// for the whole tick. Any direction will do, rounded or not, as long as both sides use the same.
// It is scaled by a power of two (exactly) to a largest component in [0.5, 1), so nothing
// overflows on finite input short of the coordinates themselves; a projection that does not
// stay finite proves nothing. The slack bounds the rounding of the projections (3 products and 2
// sums each, relative 2^-53, on coordinates up to `scale`) and of their difference.
template <size_t A, size_t B>
bool apart_along(const double* p, const double* direction, const int (&a)[A], const int (&b)[B],
                 double margin, double scale) noexcept {
  const double largest =
      std::max({std::abs(direction[0]), std::abs(direction[1]), std::abs(direction[2])});
  if (!(largest > 0.0) || !std::isfinite(largest)) return false;
  int exponent = 0;
  std::frexp(largest, &exponent);
  double n[3];
  for (int k = 0; k < 3; ++k) n[k] = std::ldexp(direction[k], -exponent);
  const auto project = [&](int i) { return dot(p + 3 * i, n); };
  double a_low = project(a[0]), a_high = a_low;
  double b_low = project(b[0]), b_high = b_low;
  bool finite = std::isfinite(a_low) && std::isfinite(b_low);
  for (size_t i = 1; i < A; ++i) {
    const double x = project(a[i]);
    finite = finite && std::isfinite(x);
    a_low = std::min(a_low, x);
    a_high = std::max(a_high, x);
  }
  for (size_t i = 1; i < B; ++i) {
    const double x = project(b[i]);
    finite = finite && std::isfinite(x);
    b_low = std::min(b_low, x);
    b_high = std::max(b_high, x);
  }
  if (!finite) return false;
  const double length = std::sqrt(dot(n, n));
  const double n1 = std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]);
  const double gap = 1.001 * margin * length + 2.0 * kErrorFactor * scale * n1 +
                     64.0 * std::numeric_limits<double>::denorm_min();
  return a_low - b_high > gap || b_low - a_high > gap;
}

// A cheap proof of no contact before the bisection: a direction along which the two swept hulls
// stay more than twice the distance tolerance apart. The bisection calls a box small when its
// image (each axis within `distance`) holds 0, i.e. |F| <= sqrt(3) distance; so this answers
// what the bisection answers, except "no contact" where the bisection would have stopped at its
// depth or iteration limit with a hit on primitives that stay more than 2 distance apart.
// Directions: the face's normal (vertex-face) or the edges' cross product (edge-edge) at the
// start and at the end of the tick, the line between the two sides' first points at the start,
// and for edges b's offset across edge a. Resting and sliding contact, primitives a thickness
// apart along a tilted normal, are what this catches: there the bisection refines for long.
template <Kind K>
bool separated(const double* p, double margin, double scale) noexcept {
  const auto apart = [&](const double* n) {
    if constexpr (K == Kind::kVertexFace)
      return apart_along(p, n, kVertexSide, kFaceSide, margin, scale);
    else
      return apart_along(p, n, kEdgeASide, kEdgeBSide, margin, scale);
  };
  for (int o = 0; o <= 4; o += 4) {  // the start of the tick, then its end
    double e1[3], e2[3];
    if constexpr (K == Kind::kVertexFace) {
      difference(p, o + 2, o + 1, e1);
      difference(p, o + 3, o + 1, e2);
    } else {
      difference(p, o + 1, o + 0, e1);
      difference(p, o + 3, o + 2, e2);
    }
    if (apart(cross(e1, e2).data())) return true;
  }
  double n[3];
  difference(p, 0, K == Kind::kVertexFace ? 1 : 2, n);
  if (apart(n)) return true;
  if constexpr (K == Kind::kEdgeEdge) {
    // Parallel edges (a structured mesh's diagonals, one surface resting on another) have no
    // cross product to go by: take b's offset from edge a's line, across edge a (n = w |d|^2 -
    // (w . d) d), at the start and at the end of the tick.
    for (int o = 0; o <= 4; o += 4) {
      double d[3], w[3];
      difference(p, o + 1, o + 0, d);
      difference(p, o + 2, o + 0, w);
      const double dd = dot(d, d), wd = dot(w, d);
      for (int k = 0; k < 3; ++k) n[k] = w[k] * dd - wd * d[k];
      if (apart(n)) return true;
    }
  }
  return false;
}

template <Kind K>
CcdResult solve(const double* p, const CcdTolerance& tolerance) noexcept {
  CcdResult result;
  std::array<double, 3> error{};
  for (int i = 0; i < 24; ++i) {
    if (!std::isfinite(p[i])) {
      result.not_finite = true;
      return result;
    }
    error[i % 3] = std::max(error[i % 3], std::abs(p[i]));
  }
  const double scale = std::max({error[0], error[1], error[2]});
  for (double& e : error) e *= kErrorFactor;
  if (tolerance.separation_test && separated<K>(p, 2.0 * tolerance.distance, scale)) return result;

  std::array<Box, kHeapCapacity> heap;
  uint32_t size = 0;
  heap[size++] = Box{0.0, 1.0, 0.0, 1.0, 0.0, 1.0, 0};
  const LaterBox later;
  uint32_t iterations = 0;
  while (size > 0) {
    std::pop_heap(heap.begin(), heap.begin() + size, later);
    const Box box = heap[--size];
    if constexpr (K == Kind::kVertexFace) {
      if (box.u0 + box.v0 > 1.0) continue;  // exact: sums of dyadic numbers of bounded depth
    }
    ++result.boxes;
    const Image image = image_of<K>(p, box, error);
    if (!image.contains_zero) continue;
    const bool small = image.width <= tolerance.distance || box.depth >= kMaxDepth;
    const bool out_of_budget = ++iterations >= tolerance.max_iterations || size + 2 > kHeapCapacity;
    if (small || out_of_budget) {
      // Every box still in the heap starts no earlier than this one (heap order).
      result.hit = true;
      result.gave_up = !small;
      result.toi = box.t0;
      result.u = 0.5 * (box.u0 + box.u1);
      result.v = 0.5 * (box.v0 + box.v1);
      return result;
    }
    const int dim =
        static_cast<int>(std::max_element(image.split_gain.begin(), image.split_gain.end()) -
                         image.split_gain.begin());
    Box low = box, high = box;
    low.depth = high.depth = box.depth + 1;
    if (dim == 0) {
      low.t1 = high.t0 = 0.5 * (box.t0 + box.t1);
    } else if (dim == 1) {
      low.u1 = high.u0 = 0.5 * (box.u0 + box.u1);
    } else {
      low.v1 = high.v0 = 0.5 * (box.v0 + box.v1);
    }
    heap[size++] = low;
    std::push_heap(heap.begin(), heap.begin() + size, later);
    heap[size++] = high;
    std::push_heap(heap.begin(), heap.begin() + size, later);
  }
  return result;
}

}  // namespace

CcdResult vertex_face_inclusion(const double* points, const CcdTolerance& tolerance) noexcept {
  return solve<Kind::kVertexFace>(points, tolerance);
}

CcdResult edge_edge_inclusion(const double* points, const CcdTolerance& tolerance) noexcept {
  return solve<Kind::kEdgeEdge>(points, tolerance);
}

}  // namespace tacta::collision
