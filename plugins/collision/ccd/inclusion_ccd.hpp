// Conservative continuous collision test for vertex-face and edge-edge over one tick.
//
// It solves the paper's Moore-Wilhelms equation (case II; case I is the same with a still
// triangle), P(t) = P0(t) + u (P1(t) - P0(t)) + v (P2(t) - P0(t)), not through the roots of
// the coplanarity cubic but by inclusion: F(t, u, v) = 0 over the box [0,1] x (u, v domain).
//
// Why it cannot miss a contact (zero false negatives):
//  1. F is trilinear in (t, u, v) for both query kinds (every term is at most t*u or t*v times
//     a constant), so on any parameter box each coordinate of F lies between the minimum and
//     the maximum of its values at the 8 box corners (a multilinear function attains its
//     extremes over a box at corners).
//  2. The corner parameters are dyadic numbers produced by halving [0,1] (fewer than 53
//     halvings), so they are exact doubles; only the evaluation of F rounds. With M the largest
//     |coordinate| of the 8 input points on that axis, every intermediate quantity is bounded
//     by 6 M and the evaluation path has at most 12 roundings, each of relative size
//     u = 2^-53; the accumulated absolute error is below 50 u M (derivation in inclusion_ccd.cpp).
//     We widen each corner interval by 2^-46 M = 128 u M, which dominates it with margin.
//  3. A box is discarded only when 0 lies outside the widened interval on some axis, so every
//     true root stays inside a kept box. Boxes are kept in a min-heap by start time; the first
//     box popped that is small enough gives the answer, and its start time is <= the time of
//     every root, hence toi is a lower bound of the true first contact time.
//  4. Every exit that is not "all boxes discarded" reports a contact: the heap overflowing and
//     the iteration limit both answer "contact" with the smallest start time still kept.
//  5. Before the bisection, a direction along which the two sides' swept hulls (each moving
//     point stays in the hull of its start and end) are more than 2 x distance apart, rounding
//     allowed for, proves no contact: every point of F then has |F| > 2 distance, which no box
//     the bisection calls small (each axis within distance) can hold. The answer is the
//     bisection's, except where it would have stopped at its limits on such a pair.
// Degenerate inputs (coplanar, parallel, zero motion, contact at t = 0 or 1, zero-area
// triangles, zero-length edges) need no special case: the argument above does not use
// any normal, determinant or division. Non-finite input returns no contact and a flag.
#pragma once

#include <cstdint>

namespace tacta::collision {

struct CcdTolerance {
  double distance = 1e-6;            // m: stop refining once the image box of F is this small
  uint32_t max_iterations = 100000;  // boxes examined before answering "contact" anyway
  // Before the bisection, look for a direction along which the two sides' swept hulls stay
  // more than 2 x distance apart (inclusion_ccd.cpp: separated); off only to compare against.
  bool separation_test = true;
};

struct CcdResult {
  bool hit = false;
  bool not_finite = false;  // input had NaN or infinity
  bool gave_up = false;     // limit or heap capacity reached: answered "contact" conservatively
  uint32_t boxes = 0;       // parameter boxes the bisection examined (0: the separation test)
  double toi = 1.0;         // lower bound of the first contact time, fraction of the tick
  double u = 0.0, v = 0.0;  // parameters at the contact (vertex-face: weights of f1, f2)
};

// points: 8 x 3 doubles as in tacta_collision_api::vertex_face / edge_edge.
CcdResult vertex_face_inclusion(const double* points, const CcdTolerance& tolerance) noexcept;
CcdResult edge_edge_inclusion(const double* points, const CcdTolerance& tolerance) noexcept;

}  // namespace tacta::collision
