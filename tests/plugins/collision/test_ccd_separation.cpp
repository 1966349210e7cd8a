// The inclusion CCD's separation test (inclusion_ccd.cpp: separated): it answers what the
// bisection answers on every reference query, and settles resting and sliding contact (surfaces
// a thickness apart along a tilted normal) without bisecting.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <string>

#include "inclusion_ccd.hpp"
#include "tacta/ccd_queries.hpp"

namespace {

using tacta::collision::CcdResult;
using tacta::collision::CcdTolerance;
using tacta::collision::edge_edge_inclusion;
using tacta::collision::vertex_face_inclusion;

CcdResult solve(const double* p, bool vertex_face, bool separation_test) {
  CcdTolerance tolerance;
  tolerance.separation_test = separation_test;
  return vertex_face ? vertex_face_inclusion(p, tolerance) : edge_edge_inclusion(p, tolerance);
}

// The query is settled by the separation test alone, and the bisection alone agrees (no contact)
// after examining more than one box.
void expect_settled_without_bisecting(const double* p, bool vertex_face, const char* label) {
  const CcdResult with = solve(p, vertex_face, true);
  const CcdResult without = solve(p, vertex_face, false);
  EXPECT_FALSE(with.hit);
  EXPECT_FALSE(without.hit);
  EXPECT_EQ(with.boxes, 0u);
  EXPECT_GT(without.boxes, 1u);
  std::printf("%s: bisection %u boxes, separation test 0\n", label, without.boxes);
}

TEST(CcdSeparation, AnswersWhatTheBisectionAnswersOnEveryReferenceQuery) {
  const auto queries = tacta::read_ccd_paths({std::string(TACTA_SOURCE_DIR) + "/tests/data/ccd"});
  ASSERT_EQ(queries.size(), 2824u);
  int settled = 0;
  for (const auto& q : queries) {
    const CcdResult with = solve(q.points, q.vertex_face, true);
    const CcdResult without = solve(q.points, q.vertex_face, false);
    if (with.boxes == 0 && !with.hit) ++settled;
    if (q.truth) {
      ASSERT_TRUE(with.hit) << "missed contact at " << q.origin;
    }
    // Where the test does not settle a query the same bisection runs: only a settled query can
    // differ, and it may only where the bisection stopped at its limits.
    if (!without.gave_up) {
      ASSERT_EQ(with.hit, without.hit) << q.origin;
    }
  }
  std::printf("separation test settled %d of %zu reference queries\n", settled, queries.size());
  // A regression guard on our own count (1,946 when written): most of these hard queries are
  // primitives near each other that a tilted direction separates.
  EXPECT_GT(settled, static_cast<int>(queries.size()) / 2);
}

// A triangle tilted 30 degrees about x, a vertex sliding 1 mm over it at 0.1 mm along the normal
// (a contact thickness): the coordinate axes do not separate them, the normal does.
TEST(CcdSeparation, SettlesAVertexRestingOnATiltedFaceWithoutBisecting) {
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6), gap = 1e-4;
  // Face points (x, y c, y s) for (x, y) in the plane; the normal is (0, -s, c).
  const double face[9] = {0, 0, 0, 0.02, 0, 0, 0, 0.02 * c, 0.02 * s};
  double p[24];
  for (int end = 0; end < 2; ++end) {
    const double x = 0.004 + 0.001 * end, y = 0.005;
    double* q = p + 12 * end;
    q[0] = x;
    q[1] = y * c - gap * s;
    q[2] = y * s + gap * c;
    for (int k = 0; k < 9; ++k) q[3 + k] = face[k];
  }
  expect_settled_without_bisecting(p, true, "resting vertex");
}

// Two crossing edges 0.1 mm apart along a tilted common normal, one sliding along the other.
TEST(CcdSeparation, SettlesCrossingEdgesAThicknessApartWithoutBisecting) {
  const double c = std::cos(M_PI / 5), s = std::sin(M_PI / 5), gap = 1e-4;
  double p[24];
  for (int end = 0; end < 2; ++end) {
    double* q = p + 12 * end;
    const double shift = 0.002 * end;
    // Edge a along x in the tilted plane, edge b along the plane's other direction, lifted.
    const double a[6] = {-0.01 + shift, 0, 0, 0.01 + shift, 0, 0};
    const double b[6] = {0, -0.01 * c - gap * s, -0.01 * s + gap * c,
                         0, 0.01 * c - gap * s,  0.01 * s + gap * c};
    for (int k = 0; k < 6; ++k) {
      q[k] = a[k];
      q[6 + k] = b[k];
    }
  }
  expect_settled_without_bisecting(p, false, "crossing edges");
}

// Parallel edges (a structured mesh's diagonals, one surface resting on another) 0.1 mm apart,
// one sliding along the other, neither along nor across a coordinate axis: no cross product to
// go by, and the line between their first points runs mostly along them; b's offset across a
// separates them.
TEST(CcdSeparation, SettlesParallelEdgesAThicknessApartWithoutBisecting) {
  const double gap = 1e-4;
  const double along[3] = {0.6, 0.64, 0.48};  // the edges' direction (unit)
  const double across = 1.0 / std::sqrt(0.64 * 0.64 + 0.6 * 0.6);
  const double normal[3] = {0.64 * across, -0.6 * across, 0.0};  // unit, normal to `along`
  double p[24];
  for (int end = 0; end < 2; ++end) {
    double* q = p + 12 * end;
    const double slide = 0.003 * end;
    const double a_from = 0.0, a_to = 0.02, b_from = 0.01 + slide, b_to = 0.03 + slide;
    for (int k = 0; k < 3; ++k) {
      q[k] = a_from * along[k];
      q[3 + k] = a_to * along[k];
      q[6 + k] = b_from * along[k] + gap * normal[k];
      q[9 + k] = b_to * along[k] + gap * normal[k];
    }
  }
  expect_settled_without_bisecting(p, false, "parallel edges");
}

// Coordinates near 1e162: the cross products overflow and the line between the sides, finite,
// gives projections that do not stay finite. A vertex passing through a still triangle at t =
// 2/3 is still a contact (a projection that overflows proves nothing).
TEST(CcdSeparation, AHugeButFiniteQueryStillFindsItsContact) {
  const double start[12] = {
      0, 0, 0, -1e152, -1e152, 0, 1e162 - 1e152, -1e162 - 1e152, -2e161, -1e152, -1e152, 1e162};
  double p[24];
  for (int k = 0; k < 12; ++k) p[k] = p[12 + k] = start[k];
  p[12] = 1e162;
  p[13] = -(1e162 + 3e152);
  p[14] = 0;
  EXPECT_TRUE(solve(p, true, true).hit);
}

}  // namespace
