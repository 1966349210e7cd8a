// BVH plugin: candidate pairs equal brute force on random deforming meshes (AABB and OBB
// nodes, body-body and self), haptic queries against brute force, a refit spread over slices and
// queries widened by a margin against a whole refit, bad input reported.
#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <set>
#include <tuple>

#include "collision_world.hpp"
#include "plugin_fixture.hpp"

namespace {

using tacta::testing::TestSurface;
using Pair = std::tuple<uint32_t, uint32_t, uint32_t, uint32_t>;

std::array<double, 6> swept_box(const TestSurface& s, uint32_t t, double margin) {
  std::array<double, 6> b{1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
  for (int i = 0; i < 3; ++i) {
    const uint32_t v = s.triangles[3 * t + i];
    for (const auto* x : {&s.start, &s.end})
      for (int k = 0; k < 3; ++k) {
        b[k] = std::min(b[k], (*x)[3 * v + k] - margin);
        b[3 + k] = std::max(b[3 + k], (*x)[3 * v + k] + margin);
      }
  }
  return b;
}

bool share_vertex(const TestSurface& s, uint32_t a, uint32_t b) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (s.triangles[3 * a + i] == s.triangles[3 * b + j]) return true;
  return false;
}

std::set<Pair> brute_force(const std::vector<TestSurface*>& surfaces, double margin) {
  std::set<Pair> pairs;
  for (uint32_t a = 0; a < surfaces.size(); ++a)
    for (uint32_t b = a; b < surfaces.size(); ++b) {
      const uint32_t na = static_cast<uint32_t>(surfaces[a]->triangles.size() / 3);
      const uint32_t nb = static_cast<uint32_t>(surfaces[b]->triangles.size() / 3);
      for (uint32_t i = 0; i < na; ++i)
        for (uint32_t j = (a == b ? i + 1 : 0); j < nb; ++j) {
          if (a == b && share_vertex(*surfaces[a], i, j)) continue;
          const auto p = swept_box(*surfaces[a], i, margin), q = swept_box(*surfaces[b], j, margin);
          bool overlap = true;
          for (int k = 0; k < 3; ++k) overlap &= p[k] <= q[3 + k] && q[k] <= p[3 + k];
          if (overlap) pairs.insert({a, i, b, j});
        }
    }
  return pairs;
}

class BvhPlugin : public ::testing::TestWithParam<int> {
 protected:
  const tacta_collision_api& api() { return plugin_.api<tacta_collision_api>("bvh"); }
  void* make(int volume) {
    auto params = tacta::testing::default_params(plugin_.descriptor("bvh"));
    params[0].number = volume;
    tacta_collision_setup setup{sizeof setup, params.data(), static_cast<uint32_t>(params.size()),
                                1e-3};
    void* instance = nullptr;
    char message[256] = {0};
    EXPECT_EQ(api().create(&setup, &instance, message, sizeof message), TACTA_OK) << message;
    return instance;
  }
  tacta::testing::LoadedPlugin plugin_{"tacta_bvh.so"};
};

// A world view over `views`, nothing else in it (dt 1 ms, no margin, no candidates).
tacta_collision_world world_over(std::vector<tacta_collision_surface>& views) {
  tacta_collision_world world{};
  world.struct_size = sizeof world;
  world.surface_count = static_cast<uint32_t>(views.size());
  world.surfaces = views.data();
  world.dt = 1e-3;
  return world;
}

TEST_P(BvhPlugin, CandidatePairsEqualBruteForceOnDeformingMeshes) {
  std::mt19937 rng(1234);
  TestSurface a = tacta::testing::grid(12, 1.0, 0.0, 0.0, 0.0);
  TestSurface b = tacta::testing::grid(9, 0.8, 0.2, 0.1, 0.05);
  const double margin = 0.002;
  std::vector<tacta_collision_surface> views{a.view(1, margin), b.view(2, margin)};
  tacta_collision_world world = world_over(views);
  void* bvh = make(GetParam());
  char message[256] = {0};
  ASSERT_EQ(api().prepare(bvh, &world, message, sizeof message), TACTA_OK) << message;
  std::vector<tacta_collision_pair> pairs(200000);
  int rebuilds = 0;
  for (int tick = 0; tick < 12; ++tick) {
    tacta::testing::deform(a, rng, 0.05, 0.3 * tick);
    tacta::testing::deform(b, rng, 0.05, -0.2 * tick);
    const uint32_t bits = api().update(bvh, &world);
    ASSERT_EQ(bits & ~TACTA_COLLIDE_REBUILT, 0u);
    rebuilds += (bits & TACTA_COLLIDE_REBUILT) != 0;
    uint32_t count = 0;
    ASSERT_EQ(
        api().find_pairs(bvh, &world, pairs.data(), static_cast<uint32_t>(pairs.size()), &count),
        0u);
    std::set<Pair> found;
    for (uint32_t i = 0; i < count; ++i)
      found.insert(
          {pairs[i].surface_a, pairs[i].element_a, pairs[i].surface_b, pairs[i].element_b});
    EXPECT_EQ(found.size(), count) << "duplicate pairs at tick " << tick;
    const auto expected = brute_force({&a, &b}, margin);
    EXPECT_GT(expected.size(), 100u);
    EXPECT_EQ(found, expected) << "tick " << tick;
  }
  EXPECT_GE(rebuilds, 1);  // the first update builds
  api().destroy(bvh);
}

TEST_P(BvhPlugin, ClosestPointAndSphereCastMatchBruteForce) {
  TestSurface a = tacta::testing::grid(10, 1.0, 0.0, 0.0, 0.0);
  std::vector<tacta_collision_surface> views{a.view(1, 0.0)};
  tacta_collision_world world = world_over(views);
  void* bvh = make(GetParam());
  char message[256] = {0};
  ASSERT_EQ(api().prepare(bvh, &world, message, sizeof message), TACTA_OK);
  api().update(bvh, &world);
  const double p[3] = {0.123, -0.2, 0.3};
  tacta_surface_hit hit{};
  ASSERT_EQ(api().closest_point(bvh, &world, 0, p, 1.0, &hit), 1);
  EXPECT_NEAR(hit.distance, 0.3, 1e-12);  // straight below onto the plane z = 0
  EXPECT_NEAR(hit.point[0], 0.123, 1e-12);
  EXPECT_NEAR(std::abs(hit.normal[2]), 1.0, 1e-12);
  // A sphere of radius 0.05 falling from z = 0.5 to z = -0.5 touches at z = 0.05: s = 0.45.
  const double from[3] = {0.1, 0.1, 0.5}, to[3] = {0.1, 0.1, -0.5};
  ASSERT_EQ(api().sphere_cast(bvh, &world, 0, from, to, 0.05, &hit), 1);
  EXPECT_NEAR(hit.toi, 0.45, 1e-9);
  EXPECT_NEAR(hit.barycentric[0] + hit.barycentric[1] + hit.barycentric[2], 1.0, 1e-12);
  // Beside the mesh: no hit.
  const double far_from[3] = {2, 2, 0.5}, far_to[3] = {2, 2, -0.5};
  EXPECT_EQ(api().sphere_cast(bvh, &world, 0, far_from, far_to, 0.05, &hit), 0);
  // A tool sphere over the middle overlaps some triangles, all near it.
  tacta_collision_shape tool{};
  tool.type = TACTA_SHAPE_SPHERE;
  tool.radius = 0.05;
  tool.pose_start = {{0, 0, 0.02}, {1, 0, 0, 0}};
  tool.pose_end = tool.pose_start;
  std::vector<uint32_t> tris(256);
  uint32_t count = 0;
  EXPECT_EQ(api().overlap_shape(bvh, &world, &tool, 0, tris.data(), 256, &count), 0u);
  EXPECT_GE(count, 2u);
  EXPECT_LE(count, 24u);
  api().destroy(bvh);
}

// The proxy's queries on a tree refit a run of its element order at a time, or not refit at all
// but widened by how far the vertices moved, answer as a tree refit whole does.
TEST_P(BvhPlugin, SlicedRefitAndWidenedQueriesAnswerAsAWholeRefit) {
  std::mt19937 rng(99);
  TestSurface a = tacta::testing::grid(20, 1.0, 0.0, 0.0, 0.0);
  std::vector<tacta_collision_surface> views{a.view(1, 0.0)};
  tacta_collision_world world = world_over(views);
  void* sliced = make(GetParam());
  void* whole = make(GetParam());
  char message[256] = {0};
  ASSERT_EQ(api().prepare(sliced, &world, message, sizeof message), TACTA_OK);
  ASSERT_EQ(api().prepare(whole, &world, message, sizeof message), TACTA_OK);
  ASSERT_NE(api().element_order, nullptr);
  ASSERT_NE(api().update_elements, nullptr);
  const uint32_t* order = nullptr;
  uint32_t total = 0;
  EXPECT_EQ(api().element_order(sliced, 0, &order, &total), TACTA_COLLIDE_UNPREPARED);
  EXPECT_EQ(api().update_elements(sliced, &world, 0, 0, 10), TACTA_COLLIDE_UNPREPARED);
  api().update(sliced, &world);
  ASSERT_EQ(api().element_order(sliced, 0, &order, &total), TACTA_COLLIDE_OK);
  ASSERT_EQ(total, 800u);
  std::vector<uint32_t> sorted(order, order + total);
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t i = 0; i < total; ++i) ASSERT_EQ(sorted[i], i) << "not a permutation";

  std::uniform_real_distribution<double> in_box(-0.6, 0.6), height(-0.3, 0.3);
  const auto same_answers = [&](const char* when) {
    for (int q = 0; q < 40; ++q) {
      const double p[3] = {in_box(rng), in_box(rng), height(rng)};
      tacta_surface_hit hs{}, hw{};
      const int fs = api().closest_point(sliced, &world, 0, p, 0.2, &hs);
      const int fw = api().closest_point(whole, &world, 0, p, 0.2, &hw);
      ASSERT_EQ(fs, fw) << when << ": closest point " << q;
      if (fw) {  // the same point (at a shared edge either triangle may report it)
        EXPECT_NEAR(hs.distance, hw.distance, 1e-12) << when;
        for (int k = 0; k < 3; ++k) EXPECT_NEAR(hs.point[k], hw.point[k], 1e-12) << when;
      }
      const double to[3] = {p[0] + 0.1, p[1] - 0.05, -p[2]};
      const int cs = api().sphere_cast(sliced, &world, 0, p, to, 0.02, &hs);
      const int cw = api().sphere_cast(whole, &world, 0, p, to, 0.02, &hw);
      ASSERT_EQ(cs, cw) << when << ": sphere cast " << q;
      if (cw) {
        EXPECT_NEAR(hs.toi, hw.toi, 1e-9) << when;
      }
    }
  };
  // Refit in runs of 64 of the order, as the engine's slices do.
  for (int tick = 0; tick < 4; ++tick) {
    tacta::testing::deform(a, rng, 0.02, 0.4 * tick);
    for (uint32_t first = 0; first < total; first += 64) {
      ASSERT_EQ(api().element_order(sliced, 0, &order, &total), TACTA_COLLIDE_OK);
      EXPECT_EQ(api().update_elements(sliced, &world, 0, first, 64), TACTA_COLLIDE_OK);
    }
    api().update(whole, &world);
    same_answers("sliced refit");
  }
  // No refit: every vertex moves by at most 5 mm, the queries widen by 5 mm.
  const double margin = 0.005;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (size_t v = 0; v < a.end.size(); v += 3) {
    double d[3] = {unit(rng), unit(rng), unit(rng)};
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + 1e-12;
    for (int k = 0; k < 3; ++k) a.end[v + k] += margin * 0.999 * d[k] / n;
  }
  a.start = a.end;
  api().update(whole, &world);
  world.query_margin = margin;
  same_answers("stale tree, widened queries");
  api().destroy(sliced);
  api().destroy(whole);
}

TEST_P(BvhPlugin, BadInputIsReportedNotCrashed) {
  void* bvh = make(GetParam());
  char message[256] = {0};
  TestSurface a = tacta::testing::grid(3, 1.0, 0.0, 0.0, 0.0);
  a.triangles[4] = 999;  // out of range
  std::vector<tacta_collision_surface> views{a.view(7, 0.0)};
  tacta_collision_world world = world_over(views);
  EXPECT_EQ(api().prepare(bvh, &world, message, sizeof message), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(message).find("999"), std::string::npos) << message;
  // NaN positions: flagged, those elements skipped.
  a.triangles[4] = 1;
  ASSERT_EQ(api().prepare(bvh, &world, message, sizeof message), TACTA_OK);
  a.end[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(api().update(bvh, &world) & TACTA_COLLIDE_NOT_FINITE, 0u);
  // Empty mesh.
  TestSurface empty;
  std::vector<tacta_collision_surface> none{empty.view(1, 0.0)};
  tacta_collision_world empty_world = world_over(none);
  ASSERT_EQ(api().prepare(bvh, &empty_world, message, sizeof message), TACTA_OK);
  api().update(bvh, &empty_world);
  uint32_t count = 5;
  tacta_collision_pair pair{};
  EXPECT_EQ(api().find_pairs(bvh, &empty_world, &pair, 1, &count), 0u);
  EXPECT_EQ(count, 0u);
  api().destroy(bvh);
}

// The host's candidates (TACTA_COLLISION_PROXY_TAKES_CANDIDATES): given every triangle the
// queries answer as the tree search does, bit for bit (of equal distances, both the lowest
// triangle); given a few, only those are tested.
TEST_P(BvhPlugin, CandidatesAnswerAsTheTreeSearchAndAreAllThatIsTested) {
  std::mt19937 rng(7);
  TestSurface a = tacta::testing::grid(16, 1.0, 0.0, 0.0, 0.0);
  tacta::testing::deform(a, rng, 0.02, 0.3);
  std::vector<tacta_collision_surface> views{a.view(1, 0.0)};
  tacta_collision_world world = world_over(views);
  void* bvh = make(GetParam());
  char message[256] = {0};
  ASSERT_EQ(api().prepare(bvh, &world, message, sizeof message), TACTA_OK);
  api().update(bvh, &world);
  std::vector<uint32_t> all(views[0].triangle_count);
  for (uint32_t t = 0; t < all.size(); ++t) all[t] = t;
  std::shuffle(all.begin(), all.end(), rng);  // the order must not matter
  std::uniform_real_distribution<double> in_box(-0.6, 0.6), height(-0.3, 0.3);
  const auto same = [](const tacta_surface_hit& x, const tacta_surface_hit& y) {
    return x.triangle == y.triangle && x.distance == y.distance && x.toi == y.toi &&
           std::equal(x.point, x.point + 3, y.point) &&
           std::equal(x.normal, x.normal + 3, y.normal);
  };
  // Grid vertices as query points too: several triangles at one distance.
  std::vector<std::array<double, 3>> points{{0.0, 0.0, 0.05}, {0.125, -0.25, 0.0}};
  for (int q = 0; q < 60; ++q) points.push_back({in_box(rng), in_box(rng), height(rng)});
  for (const auto& p : points) {
    tacta_surface_hit tree{}, listed{};
    world.proxy_candidates = nullptr;
    world.proxy_candidate_count = 0;
    const int ft = api().closest_point(bvh, &world, 0, p.data(), 0.2, &tree);
    world.proxy_candidates = all.data();
    world.proxy_candidate_count = static_cast<uint32_t>(all.size());
    const int fl = api().closest_point(bvh, &world, 0, p.data(), 0.2, &listed);
    ASSERT_EQ(ft, fl);
    if (ft) {
      EXPECT_TRUE(same(tree, listed))
          << "closest point: " << tree.triangle << ", " << listed.triangle;
    }
    const double to[3] = {p[0] + 0.1, p[1] - 0.05, -p[2]};
    world.proxy_candidates = nullptr;
    world.proxy_candidate_count = 0;
    const int ct = api().sphere_cast(bvh, &world, 0, p.data(), to, 0.02, &tree);
    world.proxy_candidates = all.data();
    world.proxy_candidate_count = static_cast<uint32_t>(all.size());
    const int cl = api().sphere_cast(bvh, &world, 0, p.data(), to, 0.02, &listed);
    ASSERT_EQ(ct, cl);
    if (ct) {
      EXPECT_TRUE(same(tree, listed))
          << "sphere cast: " << tree.triangle << ", " << listed.triangle;
    }
  }
  // Only the listed triangles (and none out of range) are tested.
  const double above[3] = {0.0, 0.0, 0.05};
  tacta_surface_hit hit{};
  world.proxy_candidates = nullptr;
  ASSERT_EQ(api().closest_point(bvh, &world, 0, above, 0.2, &hit), 1);
  const std::vector<uint32_t> far_one{999999, all[0] == hit.triangle ? all[1] : all[0]};
  world.proxy_candidates = far_one.data();
  world.proxy_candidate_count = 2;
  tacta_surface_hit only{};
  if (api().closest_point(bvh, &world, 0, above, 0.2, &only)) {
    EXPECT_EQ(only.triangle, far_one[1]);
  }
  world.proxy_candidate_count = 0;  // an empty list: nothing to touch
  EXPECT_EQ(api().closest_point(bvh, &world, 0, above, 0.2, &only), 0);
  const double down_from[3] = {0.0, 0.0, 0.5}, down_to[3] = {0.0, 0.0, -0.5};
  EXPECT_EQ(api().sphere_cast(bvh, &world, 0, down_from, down_to, 0.02, &only), 0);
  api().destroy(bvh);
}

INSTANTIATE_TEST_SUITE_P(Volumes, BvhPlugin, ::testing::Values(0, 1), [](const auto& param_info) {
  return param_info.param == 0 ? "Aabb" : "Obb";
});

}  // namespace
