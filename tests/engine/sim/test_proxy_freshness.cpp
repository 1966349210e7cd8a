// SurfaceFreshness's margins are bounds: after any motion, every vertex of a slice lies within
// the slice's margin of where it was when that slice was last refit (the property the proxy's widened
// queries rely on), and every vertex within the odometer's advance of where it was at a mark
// (the proxy's patches and free-space check rely on that), whole refits (resets) between
// included; and the slices' boxes grown by their margins keep every vertex, so no point is
// nearer the surface than clearance says (the free-space check). Checked by replaying random, local motions of a strip of triangles whose
// vertices are nodes, and of vertices that are weighted sums of four nodes (an embedded
// surface, weights outside [0, 1] included). And the point of slices that know their nodes:
// a body moving in one place refits only the slices there; nodes shaking in place refit none.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <random>
#include <vector>

#include "collision/proxy_freshness.hpp"
#include "tacta/vec3.hpp"

namespace {

using tacta::SurfaceFreshness;
constexpr uint32_t kSlice = SurfaceFreshness::kSliceElements;

// A strip of 2 x (columns + 1) vertices and 2 triangles per column, along x.
struct Strip {
  std::vector<uint32_t> triangles;
  uint32_t vertices = 0;
  explicit Strip(uint32_t columns) : vertices(2 * (columns + 1)) {
    for (uint32_t c = 0; c < columns; ++c) {
      const uint32_t a = 2 * c, b = a + 1, d = a + 2, e = a + 3;
      triangles.insert(triangles.end(), {a, d, b, b, d, e});
    }
  }
  uint32_t count() const { return static_cast<uint32_t>(triangles.size() / 3); }
};

// Vertex positions from node positions: `nodes_per_vertex` weighted nodes each (or the node).
std::vector<double> vertex_positions(const std::vector<double>& nodes, uint32_t vertices,
                                     const std::vector<uint32_t>& vertex_nodes,
                                     const std::vector<double>& weights, uint32_t per_vertex) {
  std::vector<double> out(3 * size_t{vertices}, 0.0);
  for (uint32_t v = 0; v < vertices; ++v)
    for (uint32_t j = 0; j < per_vertex; ++j) {
      const uint32_t n = per_vertex == 1 ? v : vertex_nodes[per_vertex * v + j];
      const double w = per_vertex == 1 ? 1.0 : weights[per_vertex * v + j];
      for (int a = 0; a < 3; ++a) out[3 * v + a] += w * nodes[3 * n + a];
    }
  return out;
}

double segment_distance(const tacta::Vec3& p, const tacta::Vec3& a, const tacta::Vec3& b) {
  const tacta::Vec3 ab = tacta::sub(b, a);
  const double ab2 = tacta::dot(ab, ab);  // m^2
  const double t = ab2 > 0 ? std::clamp(tacta::dot(tacta::sub(p, a), ab) / ab2, 0.0, 1.0) : 0.0;
  return tacta::distance(tacta::add_scaled(a, ab, t), p);
}

// The exact distance (m) from p to the triangles: to the plane where p's foot falls inside a
// triangle (by the signs of the three sub-areas), else to the nearest of its edges.
double surface_distance(const tacta::Vec3& p, const std::vector<double>& vertices,
                        const std::vector<uint32_t>& triangles) {
  double least = 1e300;
  for (size_t t = 0; t < triangles.size(); t += 3) {
    const tacta::Vec3 x[3] = {tacta::point_at(vertices.data(), triangles[t]),
                              tacta::point_at(vertices.data(), triangles[t + 1]),
                              tacta::point_at(vertices.data(), triangles[t + 2])};
    for (int e = 0; e < 3; ++e) least = std::min(least, segment_distance(p, x[e], x[(e + 1) % 3]));
    const tacta::Vec3 n = tacta::cross(tacta::sub(x[1], x[0]), tacta::sub(x[2], x[0]));
    if (!(tacta::dot(n, n) > 0)) continue;
    bool inside = true;
    for (int e = 0; e < 3; ++e)
      inside =
          inside && tacta::triple(n, tacta::sub(x[(e + 1) % 3], x[e]), tacta::sub(p, x[e])) >= 0;
    if (inside)
      least = std::min(least, std::fabs(tacta::dot(n, tacta::sub(p, x[0]))) / tacta::norm(n));
  }
  return least;
}

// Random local motion for `ticks` ticks; every tick, each slice's vertices are checked against
// where they were at that slice's last refit, and clearance against points near the strip.
// Returns the slices refit.
uint64_t replay(uint32_t per_vertex, uint64_t seed) {
  const Strip strip(700);  // 1,400 triangles: 11 slices
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  // Nodes: the vertices themselves, or a coarser set each vertex follows four of.
  const uint32_t node_count = per_vertex == 1 ? strip.vertices : strip.vertices / 4 + 4;
  std::vector<uint32_t> vertex_nodes;
  std::vector<double> weights;
  double weight_bound = 1.0;
  for (uint32_t v = 0; per_vertex > 1 && v < strip.vertices; ++v) {
    double sum = 0, abs_sum = 0;
    std::array<double, 4> w{};
    for (uint32_t j = 0; j < 4; ++j) {
      vertex_nodes.push_back(std::min(node_count - 1, v / 4 + j));
      w[j] = 0.25 + 0.4 * unit(rng);  // some below 0: extrapolated
      sum += w[j];
    }
    for (double& x : w) {
      x /= sum;
      abs_sum += std::fabs(x);
      weights.push_back(x);
    }
    weight_bound = std::max(weight_bound, abs_sum);
  }
  std::vector<double> nodes(3 * size_t{node_count});
  for (uint32_t n = 0; n < node_count; ++n) nodes[3 * n] = 0.01 * n;
  // A scrambled element order, as a hierarchy's is.
  std::vector<uint32_t> order(strip.count());
  for (uint32_t e = 0; e < strip.count(); ++e) order[e] = e;
  std::shuffle(order.begin(), order.end(), rng);

  const double target = 1e-3, cap = 1.0;  // m
  SurfaceFreshness fresh(node_count, strip.count(), weight_bound, target, cap, per_vertex);
  fresh.reset(nodes.data());
  fresh.bind(order.data(), strip.triangles.data(), per_vertex == 1 ? nullptr : vertex_nodes.data());
  const uint32_t slices = (strip.count() + kSlice - 1) / kSlice;
  // Each slice's box, as the collision context gives it: from its vertices where they are when
  // the slice (or everything) is refit.
  const auto box_slice = [&](uint32_t slice, const std::vector<double>& at) {
    std::array<double, 6> box{1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (uint32_t e = slice * kSlice; e < std::min(strip.count(), (slice + 1) * kSlice); ++e)
      for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) {
          const double x = at[3 * size_t{strip.triangles[3 * order[e] + c]} + a];
          box[a] = std::min(box[a], x);
          box[a + 3] = std::max(box[a + 3], x);
        }
    fresh.set_slice_box(slice * kSlice, box);
  };
  EXPECT_EQ(fresh.clearance(nodes.data(), 1.0), 0.0) << "no box yet";
  for (uint32_t s = 0; s < slices; ++s)
    box_slice(s, vertex_positions(nodes, strip.vertices, vertex_nodes, weights, per_vertex));
  uint64_t clear_points = 0;
  std::vector<std::vector<double>> at_refit(
      slices, vertex_positions(nodes, strip.vertices, vertex_nodes, weights, per_vertex));
  std::vector<double> at_mark = at_refit[0];
  double base_at_mark = fresh.odometer_base();
  uint64_t refits = 0;
  for (int tick = 0; tick < 2000; ++tick) {
    if (tick % 61 == 0) {  // a patch gathered, a closest point found
      base_at_mark = fresh.odometer_base();
      at_mark = vertex_positions(nodes, strip.vertices, vertex_nodes, weights, per_vertex);
    }
    if (tick % 333 == 150) {  // the nodes move after the tick's advance, then a whole refit
      for (double& x : nodes) x += 1e-2 * unit(rng);  // m: past any path summed since the mark
      fresh.reset(nodes.data());
      for (auto& slice : at_refit)
        slice = vertex_positions(nodes, strip.vertices, vertex_nodes, weights, per_vertex);
      EXPECT_EQ(fresh.clearance(nodes.data(), 1.0), 0.0) << "a reset forgets the boxes";
      for (uint32_t s = 0; s < slices; ++s) box_slice(s, at_refit[s]);
    }
    // A patch of nodes moves (the tool's neighbourhood, somewhere along the strip), plus a
    // slow drift of everything now and then.
    const auto centre = static_cast<uint32_t>(rng() % node_count);
    for (uint32_t n = centre; n < std::min(node_count, centre + 30); ++n)
      for (int a = 0; a < 3; ++a) nodes[3 * n + a] += 2e-4 * unit(rng);
    if (tick % 97 == 0)
      for (double& x : nodes) x += 1e-5 * unit(rng);
    EXPECT_TRUE(fresh.advance(nodes.data())) << "the cap is far";
    const std::vector<double> now =
        vertex_positions(nodes, strip.vertices, vertex_nodes, weights, per_vertex);
    for (uint32_t v = 0; v < strip.vertices; ++v) {
      const double dx = now[3 * v] - at_mark[3 * v], dy = now[3 * v + 1] - at_mark[3 * v + 1],
                   dz = now[3 * v + 2] - at_mark[3 * v + 2];
      const double moved = std::sqrt(dx * dx + dy * dy + dz * dz);
      const double odometer = fresh.odometer() - base_at_mark;
      if (moved > odometer * (1 + 1e-12) + 1e-15) {
        ADD_FAILURE() << "vertex " << v << " moved " << moved << " m since the mark, the odometer "
                      << odometer << " m at tick " << tick;
        return refits;
      }
    }
    // Points up to 3 cm from a vertex: none nearer the strip than its clearance.
    for (int k = 0; k < 4; ++k) {
      const uint32_t v = static_cast<uint32_t>(rng() % strip.vertices);
      const std::array<double, 3> p{now[3 * v] + 0.03 * unit(rng),
                                    now[3 * v + 1] + 0.03 * unit(rng),
                                    now[3 * v + 2] + 0.03 * unit(rng)};
      const double bound = fresh.clearance(p.data(), 1.0);
      const double exact = surface_distance(p, now, strip.triangles);
      if (bound > exact * (1 + 1e-12) + 1e-15) {
        ADD_FAILURE() << "clearance " << bound << " m past the distance " << exact << " m at tick "
                      << tick;
        return refits;
      }
      clear_points += bound > 0.0 ? 1 : 0;
    }
    for (uint32_t s = 0; s < slices; ++s)
      for (uint32_t e = s * kSlice; e < std::min(strip.count(), (s + 1) * kSlice); ++e)
        for (int c = 0; c < 3; ++c) {
          const uint32_t v = strip.triangles[3 * order[e] + c];
          const double dx = now[3 * v] - at_refit[s][3 * v],
                       dy = now[3 * v + 1] - at_refit[s][3 * v + 1],
                       dz = now[3 * v + 2] - at_refit[s][3 * v + 2];
          const double moved = std::sqrt(dx * dx + dy * dy + dz * dz);
          if (moved > fresh.slice_margin(s) * (1 + 1e-12) + 1e-15) {
            ADD_FAILURE() << "slice " << s << " vertex " << v << " moved " << moved
                          << " m, its margin " << fresh.slice_margin(s) << " m at tick " << tick;
            return refits;
          }
        }
    // A call refits one slice or measures a few: as many calls as slices bring the margin
    // under its target.
    for (uint32_t call = 0; call <= slices; ++call) {
      uint32_t first = 0, count = 0;
      fresh.next_slice(first, count);
      if (count == 0) continue;
      at_refit[first / kSlice] = now;  // the slice's boxes are computed from where it is now
      box_slice(first / kSlice, now);
      ++refits;
    }
    EXPECT_LE(fresh.margin(), target);
  }
  std::printf("%llu of 8,000 points found clear\n", static_cast<unsigned long long>(clear_points));
  EXPECT_GT(clear_points, 250u) << "of 8,000 points up to 3 cm from a vertex";
  return refits;
}

TEST(ProxyFreshness, MarginsBoundWhereSlicesOfNodeVerticesMoved) { EXPECT_GT(replay(1, 1), 0u); }

TEST(ProxyFreshness, MarginsBoundWhereSlicesOfEmbeddedVerticesMoved) {
  EXPECT_GT(replay(4, 2), 0u);
}

// A straight strip whose vertices are nodes, in element order, its freshness bound to it.
struct BoundStrip {
  Strip strip{700};
  std::vector<double> nodes;
  std::vector<uint32_t> order;
  SurfaceFreshness fresh;
  explicit BoundStrip(double target)
      : nodes(3 * size_t{strip.vertices}),
        order(strip.count()),
        fresh(strip.vertices, strip.count(), 1.0, target, 1.0, 1) {
    for (uint32_t n = 0; n < strip.vertices; ++n) nodes[3 * n] = 0.01 * n;
    for (uint32_t e = 0; e < strip.count(); ++e) order[e] = e;
    fresh.reset(nodes.data());
    fresh.bind(order.data(), strip.triangles.data(), nullptr);
  }
};

// The bound reads only what is known: nothing before the boxes, nothing for a point or node not
// finite; the limit caps it; a point inside a slice's box grown by its margin gets 0.
TEST(ProxyFreshness, ClearanceIsZeroWhereNothingIsKnown) {
  BoundStrip bound(1e-3);
  SurfaceFreshness& fresh = bound.fresh;
  const std::array<double, 3> above{0.5, 0.0, 0.2};  // m: 20 cm over the strip's middle
  EXPECT_EQ(fresh.clearance(above.data(), 1.0), 0.0);
  const uint32_t slices = (bound.strip.count() + kSlice - 1) / kSlice;
  for (uint32_t s = 0; s < slices; ++s) {
    std::array<double, 6> box{1e300, 1e300, 0.0, -1e300, -1e300, 0.0};
    for (uint32_t e = s * kSlice; e < std::min(bound.strip.count(), (s + 1) * kSlice); ++e)
      for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 2; ++a) {
          const double x = bound.nodes[3 * size_t{bound.strip.triangles[3 * e + c]} + a];
          box[a] = std::min(box[a], x);
          box[a + 3] = std::max(box[a + 3], x);
        }
    fresh.set_slice_box(s * kSlice, box);
  }
  EXPECT_NEAR(fresh.clearance(above.data(), 1.0), 0.2, 1e-15);
  EXPECT_EQ(fresh.clearance(above.data(), 0.05), 0.05);  // searched no further
  const std::array<double, 3> on{0.5, 0.0, 0.0005};      // within the margin to come
  bound.nodes[2] += 1e-3;                                // slice 0 rises 1 mm
  ASSERT_TRUE(fresh.advance(bound.nodes.data()));
  EXPECT_NEAR(fresh.clearance(above.data(), 1.0), 0.2 - 1e-3, 1e-12);
  EXPECT_EQ(fresh.clearance(on.data(), 1.0), 0.0);
  const std::array<double, 3> nan{std::nan(""), 0.0, 0.2};
  EXPECT_EQ(fresh.clearance(nan.data(), 1.0), 0.0);
  bound.nodes[5] = std::nan("");
  fresh.advance(bound.nodes.data());
  EXPECT_EQ(fresh.clearance(above.data(), 1.0), 0.0);
}

// One end of the strip moves; the slices at the other end are never refit.
TEST(ProxyFreshness, StillSlicesAreNotRefit) {
  BoundStrip bound(1e-3);
  std::vector<double>& nodes = bound.nodes;
  SurfaceFreshness& fresh = bound.fresh;
  uint32_t highest_refit = 0;
  for (int tick = 0; tick < 500; ++tick) {
    for (uint32_t n = 0; n < 40; ++n) nodes[3 * n + 2] += 1e-4;  // the first 20 columns rise
    ASSERT_TRUE(fresh.advance(nodes.data()));
    uint32_t first = 0, count = 0;
    for (fresh.next_slice(first, count); count > 0; fresh.next_slice(first, count))
      highest_refit = std::max(highest_refit, first + count);
  }
  // The 40 nodes belong to the first 40 triangles, all in slice 0.
  EXPECT_EQ(highest_refit, kSlice);
}

// Nodes shaking in place (a settling body, a vibrating one) add path every tick but stay within
// a quarter of the target of where they were: each slice is measured and none is refit, though
// the path sums pass the target after two ticks. A slice the shaking carries away is refit.
TEST(ProxyFreshness, NodesShakingInPlaceAreMeasuredNotRefit) {
  const double target = 1e-3;  // m
  BoundStrip bound(target);
  std::vector<double>& nodes = bound.nodes;
  SurfaceFreshness& fresh = bound.fresh;
  uint64_t refits = 0;
  for (int tick = 0; tick < 500; ++tick) {
    const double sign = tick % 2 == 0 ? 1.0 : -1.0;
    for (uint32_t n = 0; n < bound.strip.vertices; ++n) nodes[3 * n + 2] = 0.2 * target * sign;
    ASSERT_TRUE(fresh.advance(nodes.data()));
    uint32_t first = 0, count = 0;
    for (fresh.next_slice(first, count); count > 0; fresh.next_slice(first, count)) ++refits;
    // 22 slices cross together and 8 are measured a tick: the others wait with their path sums.
    ASSERT_LE(fresh.margin(), 2 * target);
  }
  EXPECT_EQ(refits, 0u) << "path sums of 0.4 target a tick, displacements of 0.2 target";
  // The first slice's nodes now move off by a whole target: that slice alone is refit.
  for (uint32_t n = 0; n < 40; ++n) nodes[3 * n + 2] += target;
  ASSERT_TRUE(fresh.advance(nodes.data()));
  uint32_t first = 0, count = 0, highest = 0;
  for (fresh.next_slice(first, count); count > 0; fresh.next_slice(first, count)) {
    ++refits;
    highest = std::max(highest, first + count);
  }
  EXPECT_EQ(refits, 1u);
  EXPECT_EQ(highest, kSlice);
}

}  // namespace
