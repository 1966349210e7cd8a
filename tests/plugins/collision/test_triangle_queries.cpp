// The proxy's sphere cast against one triangle (bvh plugin, triangle_queries.hpp): its closed
// form against the first touch found by marching the distance to the triangle along the sweep,
// on random triangles and sweeps and on the cases where a closed form can slip (a start within
// r, a sweep along the face, across an edge or onto a corner, flat and needle triangles).
#include <gtest/gtest.h>
#include <random>

#include "triangle_queries.hpp"

namespace {

using tacta::Vec3;
using tacta::collision::distance_to_triangle;
using tacta::collision::sphere_cast_triangle;

// The first s in [0, 1] with distance <= r, by steps of 1/20000 then bisection to 1e-14: exact
// but for touches shorter than a step (grazes), which the random cases below rarely make.
double marched(const Vec3& from, const Vec3& to, double r, const Vec3& a, const Vec3& b,
               const Vec3& c) {
  auto gap = [&](double s) {
    return distance_to_triangle(tacta::add_scaled(from, tacta::sub(to, from), s), a, b, c) - r;
  };
  if (gap(0.0) <= 0.0) return 0.0;
  constexpr int kSteps = 20000;
  for (int i = 1; i <= kSteps; ++i) {
    const double hi = static_cast<double>(i) / kSteps;
    if (gap(hi) > 0.0) continue;
    double lo = static_cast<double>(i - 1) / kSteps, top = hi;
    while (top - lo > 1e-14) {
      const double mid = 0.5 * (lo + top);
      (gap(mid) > 0.0 ? lo : top) = mid;
    }
    return top;
  }
  return -1.0;
}

TEST(SphereCastTriangle, FirstTouchEqualsTheMarchedDistance) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto point = [&] { return Vec3{unit(random), unit(random), unit(random)}; };
  int hits = 0, misses = 0, grazes = 0;
  for (int i = 0; i < 1500; ++i) {
    const Vec3 a = point(), b = point(), c = point(), from = tacta::scaled(point(), 2.0),
               to = tacta::scaled(point(), 2.0);
    const double r = 0.05 + 0.3 * (0.5 + 0.5 * unit(random));
    const double s = sphere_cast_triangle(from, to, r, a, b, c);
    const double reference = marched(from, to, r, a, b, c);
    if (reference < 0.0 && s >= 0.0) {
      // A graze the march stepped over: the cast's contact must be real (within r then).
      const Vec3 at = tacta::add_scaled(from, tacta::sub(to, from), s);
      EXPECT_LE(distance_to_triangle(at, a, b, c), r * (1.0 + 1e-9)) << i;
      ++grazes;
      continue;
    }
    ASSERT_EQ(s >= 0.0, reference >= 0.0) << i << ": cast " << s << ", marched " << reference;
    if (s < 0.0) {
      ++misses;
      continue;
    }
    ++hits;
    EXPECT_NEAR(s, reference, 1e-9) << i;
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 300);
  EXPECT_LT(grazes, 10);
}

TEST(SphereCastTriangle, FaceEdgeCornerAndStartCases) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const double r = 0.1;
  // Straight down onto the face: touches when the centre is r above it.
  EXPECT_NEAR(sphere_cast_triangle({0.2, 0.2, 1.1}, {0.2, 0.2, -0.9}, r, a, b, c), 0.5, 1e-15);
  // From below as well (either side).
  EXPECT_NEAR(sphere_cast_triangle({0.2, 0.2, -1.1}, {0.2, 0.2, 0.9}, r, a, b, c), 0.5, 1e-15);
  // Sideways at height r / 2 into the edge x = 0: the cylinder around it, at x = -r.
  EXPECT_NEAR(sphere_cast_triangle({-1, 0.3, 0.0}, {1, 0.3, 0.0}, r, a, b, c), 0.45, 1e-15);
  // Along the diagonal out of the corner a: the corner's sphere, at distance r from a.
  const double back = 1.0 / std::sqrt(2.0);
  EXPECT_NEAR(sphere_cast_triangle({-back, -back, 0}, {0, 0, 0}, r, a, b, c), 0.9, 1e-12);
  // Parallel to the face at height 2r: never touches.
  EXPECT_LT(sphere_cast_triangle({-1, 0.2, 0.2}, {2, 0.2, 0.2}, r, a, b, c), 0.0);
  // A start within r touches at 0; no motion and apart: no touch.
  EXPECT_EQ(sphere_cast_triangle({0.2, 0.2, 0.05}, {0.2, 0.2, 1}, r, a, b, c), 0.0);
  EXPECT_LT(sphere_cast_triangle({0.2, 0.2, 1}, {0.2, 0.2, 1}, r, a, b, c), 0.0);
  // A flat (collinear) triangle is its edges: the sweep meets the segment's cylinder.
  EXPECT_NEAR(sphere_cast_triangle({0.5, -1, 0}, {0.5, 1, 0}, r, a, b, {2, 0, 0}), 0.45, 1e-15);
  // A needle (all three corners at one point) is that point.
  EXPECT_NEAR(sphere_cast_triangle({-1, 0, 0}, {1, 0, 0}, r, a, a, a), 0.45, 1e-15);
}

// A proxy sliding over a face (its plane test's case): ends on one side further than r from the
// plane never touch; one end within r does, at once or where the sweep comes within r.
TEST(SphereCastTriangle, SweepsAlongThePlaneTouchOnlyWithinR) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const double r = 0.1;
  EXPECT_LT(sphere_cast_triangle({0.2, 0.2, r + 1e-9}, {0.3, 0.2, r + 1e-9}, r, a, b, c), 0.0);
  EXPECT_LT(sphere_cast_triangle({0.2, 0.2, -r - 1e-9}, {0.3, 0.2, -r - 1e-9}, r, a, b, c), 0.0);
  EXPECT_EQ(sphere_cast_triangle({0.2, 0.2, r - 1e-9}, {0.3, 0.2, r}, r, a, b, c), 0.0);
  // Sinking from 2r to r / 2 over the face: touches half way down (height r), as marched.
  const Vec3 from{0.2, 0.2, 2 * r}, to{0.3, 0.2, 0.5 * r};
  EXPECT_NEAR(sphere_cast_triangle(from, to, r, a, b, c), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(sphere_cast_triangle(from, to, r, a, b, c), marched(from, to, r, a, b, c), 1e-9);
  // Ends on opposite sides (through the plane, past the triangle's edge): the edge's cylinder.
  EXPECT_NEAR(sphere_cast_triangle({-0.5, 0.2, 1}, {-0.5, 0.2, -1}, r, a, b, c), -1.0, 0.0);
  const Vec3 across_from{-0.05, 0.2, 1}, across_to{-0.05, 0.2, -1};
  EXPECT_NEAR(sphere_cast_triangle(across_from, across_to, r, a, b, c),
              marched(across_from, across_to, r, a, b, c), 1e-9);
}

// A sliver (three corners on a line, up to rounding) has no plane to test against: its normal is
// rounding noise. A 4 mm sphere starting on the sliver touches it at once, whatever the noise.
TEST(SphereCastTriangle, ASweepStartingOnASliverTouchesAtOnce) {
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int wrong = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 a{0.04 * unit(random), 0.04 * unit(random), 0.04 * unit(random)};
    const Vec3 d{0.01 * unit(random), 0.01 * unit(random), 0.01 * unit(random)};
    const Vec3 b = tacta::add_scaled(a, d, 1.0),
               c = tacta::add_scaled(a, d, 0.5 * (1 + unit(random)));
    const Vec3 from = tacta::add_scaled(a, d, 0.5), to = tacta::add_scaled(from, {1, 0, 0}, 1e-4);
    wrong += sphere_cast_triangle(from, to, 0.004, a, b, c) == 0.0 ? 0 : 1;
  }
  EXPECT_EQ(wrong, 0);
}

}  // namespace
