// ProxyPatch's bookkeeping: a query is answered from the patch only while its box lies inside
// the gathered cube shrunk by how far the surface's odometer advanced since; the next cube holds
// the queries served; a gather that held too many triangles is not tried again for as large a
// query for a while, twice as long after each further failure in a row (one a pass), until a
// query of that size fits or the surface changes.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <vector>

#include "collision/proxy_patch.hpp"

namespace {

using tacta::ProxyPatch;

ProxyPatch::Box box_about(double x, double y, double z, double half) {
  return {x - half, y - half, z - half, x + half, y + half, z + half};
}

TEST(ProxyPatch, CoversOnlyInsideTheCubeLessTheTravel) {
  ProxyPatch patch;
  EXPECT_FALSE(patch.covers(box_about(0, 0, 0, 1e-3), 0.0));  // nothing gathered yet
  const std::vector<uint32_t> found{4, 8, 15};
  // Gathered with the surface's odometer at 0.002 m.
  ASSERT_TRUE(patch.keep({0, 0, 0}, 0.01, found.data(), 3, box_about(0, 0, 0, 0.005), 1, 0.002));
  EXPECT_EQ(patch.count(), 3u);
  EXPECT_TRUE(patch.covers(box_about(0, 0, 0, 0.005), 0.002));
  EXPECT_TRUE(patch.covers(box_about(0.004, 0, 0, 0.005), 0.003));  // 9 mm of 10 - 1
  EXPECT_FALSE(patch.covers(box_about(0.004, 0, 0, 0.005), 0.0035));
  EXPECT_FALSE(patch.covers(box_about(0, 0, -0.006, 0.005), 0.002));  // out along z
  EXPECT_FALSE(patch.covers(box_about(0, 0, 0, 0.005), std::nan("")));
  EXPECT_FALSE(patch.covers(box_about(0, 0, 0, 0.005), 0.001));  // an odometer run back
  patch.drop();
  EXPECT_FALSE(patch.covers(box_about(0, 0, 0, 1e-3), 0.002));
}

TEST(ProxyPatch, TheNextCubeHoldsTheQueriesServed) {
  ProxyPatch patch;
  const std::vector<uint32_t> none;
  ASSERT_TRUE(patch.keep({0, 0, 0}, 0.01, none.data(), 0, box_about(0, 0, 0, 0.005), 1, 0.0));
  patch.note_served(box_about(0, 0, 0, 0.004));  // a closest point's ball: 8 mm across
  std::array<double, 3> center{};
  double half = 0;
  patch.cube_for(box_about(1, 2, 3, 0.001), false, center, half);  // a short sweep's box
  EXPECT_EQ(center, (std::array<double, 3>{1, 2, 3}));
  EXPECT_NEAR(half, 0.008, 1e-15);
  EXPECT_TRUE(patch.widens(box_about(1, 2, 3, 0.001)));
  patch.cube_for(box_about(1, 2, 3, 0.001), true, center, half);
  EXPECT_NEAR(half, 0.002, 1e-15);  // that box alone: its side
  EXPECT_FALSE(patch.widens(box_about(1, 2, 3, 0.006)));
}

TEST(ProxyPatch, TooManyTrianglesAreNotKeptNorSoughtAgainForAsLargeAQuery) {
  ProxyPatch patch;
  const std::vector<uint32_t> few{1, 2};
  ASSERT_TRUE(patch.keep({0, 0, 0}, 0.01, few.data(), 2, box_about(0, 0, 0, 0.005), 1, 0.0));
  std::vector<uint32_t> many(ProxyPatch::kCapacity + 1);
  const ProxyPatch::Box large = box_about(0, 0, 0, 0.02);
  EXPECT_FALSE(
      patch.keep({0, 0, 0}, 0.04, many.data(), ProxyPatch::kCapacity + 1, large, 10, 0.001));
  EXPECT_EQ(patch.count(), 2u);  // the patch is as it was
  EXPECT_TRUE(patch.covers(box_about(0, 0, 0, 0.005), 0.0));
  EXPECT_FALSE(patch.worth_gathering(large, 11));
  EXPECT_FALSE(patch.worth_gathering(box_about(0, 0, 0, 0.016), 11));  // 4/5 of the side
  EXPECT_TRUE(patch.worth_gathering(box_about(0, 0, 0, 0.01), 11));    // half the side
  EXPECT_TRUE(patch.worth_gathering(large, 10 + 64));                  // tried again later
}

TEST(ProxyPatch, AQueryThatKeepsFailingIsTriedAgainLessOftenUntilItFits) {
  ProxyPatch patch;
  std::vector<uint32_t> many(ProxyPatch::kCapacity + 1);
  const uint32_t too_many = ProxyPatch::kCapacity + 1;
  const ProxyPatch::Box large = box_about(0, 0, 0, 0.02);
  uint64_t pass = 100;
  // Failures in a row wait 64, 128, 256, 512, then 1,024 passes at most.
  for (uint64_t wait : {64u, 128u, 256u, 512u, 1024u, 1024u}) {
    ASSERT_FALSE(patch.keep({0, 0, 0}, 0.04, many.data(), too_many, large, pass, 0.0));
    EXPECT_FALSE(patch.worth_gathering(large, pass + wait - 1)) << wait;
    EXPECT_TRUE(patch.worth_gathering(large, pass + wait)) << wait;
    pass += wait;
  }
  // A smaller query's patch does not end the run of failures; one of the failed size does.
  const std::vector<uint32_t> few{1, 2};
  ASSERT_TRUE(patch.keep({0, 0, 0}, 0.01, few.data(), 2, box_about(0, 0, 0, 0.005), pass, 0.0));
  ASSERT_FALSE(patch.keep({0, 0, 0}, 0.04, many.data(), too_many, large, pass + 1, 0.0));
  EXPECT_FALSE(patch.worth_gathering(large, pass + 1 + 1023));
  ASSERT_TRUE(patch.keep({0, 0, 0}, 0.04, few.data(), 2, large, pass + 1024, 0.0));
  ASSERT_FALSE(patch.keep({0, 0, 0}, 0.04, many.data(), too_many, large, pass + 2000, 0.0));
  EXPECT_TRUE(patch.worth_gathering(large, pass + 2000 + 64));
  // A failure of a query of another size starts a new run.
  ASSERT_FALSE(patch.keep({0, 0, 0}, 0.04, many.data(), too_many, large, pass + 3000, 0.0));
  const ProxyPatch::Box larger = box_about(0, 0, 0, 0.04);
  ASSERT_FALSE(patch.keep({0, 0, 0}, 0.08, many.data(), too_many, larger, pass + 3001, 0.0));
  EXPECT_TRUE(patch.worth_gathering(larger, pass + 3001 + 64));
  // Two failures in one pass (the cube served, then the query alone) count once.
  pass += 4000;
  ASSERT_FALSE(patch.keep({0, 0, 0}, 0.08, many.data(), too_many, larger, pass, 0.0));
  ASSERT_FALSE(patch.keep({0, 0, 0}, 0.04, many.data(), too_many, larger, pass, 0.0));
  EXPECT_TRUE(patch.worth_gathering(larger, pass + 128));  // the second failure in a row
  ASSERT_FALSE(patch.keep({0, 0, 0}, 0.08, many.data(), too_many, larger, pass + 128, 0.0));
  EXPECT_FALSE(patch.worth_gathering(larger, pass + 128 + 255));
  // A changed surface starts afresh.
  patch.drop();
  EXPECT_TRUE(patch.worth_gathering(larger, pass + 129));
}

// The cube for the queries served held too many, the query's own cube fit: queries of that size
// are gathered for again at once (they fit), not left to the hierarchy for the next 64 passes.
TEST(ProxyPatch, AQueryOfTheSizeThatFailedIsGatheredForOnceOneFits) {
  ProxyPatch patch;
  std::vector<uint32_t> many(ProxyPatch::kCapacity + 1);
  const std::vector<uint32_t> few{1, 2};
  const ProxyPatch::Box query = box_about(0, 0, 0, 0.0045);
  ASSERT_FALSE(patch.keep({0, 0, 0}, 0.02, many.data(), ProxyPatch::kCapacity + 1, query, 7, 0));
  EXPECT_FALSE(patch.worth_gathering(query, 8));
  ASSERT_TRUE(patch.keep({0, 0, 0}, 0.009, few.data(), 2, query, 7, 0.0));
  EXPECT_TRUE(patch.worth_gathering(query, 8));
  EXPECT_TRUE(patch.worth_gathering(box_about(0.01, 0, 0, 0.0045), 9));
}

// meeting() answers as a test of every box would, in the patch's order, whether a query falls
// inside the grown box of an earlier one (the triangles that met it) or not (all of them); new
// boxes or a NaN query start again.
TEST(ProxyPatch, MeetingFindsEveryTriangleWhoseBoxMeetsTheQuery) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  ProxyPatch patch;
  // The patch's triangles are surface triangles 1000 + 7 k (not their places in the patch).
  std::vector<uint32_t> triangles(ProxyPatch::kCapacity);
  for (uint32_t t = 0; t < triangles.size(); ++t) triangles[t] = 1000 + 7 * t;
  ASSERT_TRUE(patch.keep({0, 0, 0}, 0.02, triangles.data(), ProxyPatch::kCapacity,
                         box_about(0, 0, 0, 0.005), 1, 0.0));
  std::vector<double> positions(9 * triangles.size());  // three corners a triangle, m
  const auto scatter = [&] {  // triangles of about 3 mm anywhere in a 4 cm cube
    for (size_t t = 0; t < triangles.size(); ++t) {
      std::array<double, 3> centre{0.02 * unit(rng), 0.02 * unit(rng), 0.02 * unit(rng)};
      for (size_t c = 0; c < 3; ++c)
        for (size_t a = 0; a < 3; ++a)
          positions[9 * t + 3 * c + a] = centre[a] + 0.0015 * unit(rng);
    }
  };
  // Surface triangle 1000 + 7 k has corners 3k, 3k + 1, 3k + 2 of `positions`.
  std::vector<uint32_t> corners(3 * (1000 + 7 * triangles.size()));
  for (uint32_t t = 0; t < triangles.size(); ++t)
    for (uint32_t c = 0; c < 3; ++c) corners[3 * size_t{triangles[t]} + c] = 3 * t + c;
  std::vector<uint32_t> found(ProxyPatch::kCapacity);
  uint64_t met = 0;
  // The same place each round: the triangles that met it last round must not be taken again.
  const ProxyPatch::Box first = box_about(0.005, -0.003, 0, 0.004);
  for (int round = 0; round < 4; ++round) {
    scatter();
    patch.set_boxes(positions.data(), corners.data(), static_cast<uint64_t>(round + 1));
    for (int q = 0; q < 200; ++q) {
      // Queries near the first (the proxy's iterations) and anywhere in the patch.
      ProxyPatch::Box box = first;
      const double shift = q % 2 == 0 ? 0.001 : 0.02;
      for (int a = 0; a < 3; ++a) {
        const double d = shift * unit(rng);
        box[a] += d;
        box[a + 3] += d;
      }
      if (q == 150) box[0] = std::nan("");
      std::vector<uint32_t> expected;
      for (uint32_t t = 0; t < triangles.size(); ++t) {
        bool apart = false;
        for (size_t a = 0; a < 3; ++a) {
          double lo = 1e300, hi = -1e300;
          for (size_t c = 0; c < 3; ++c) {
            lo = std::min(lo, positions[9 * t + 3 * c + a]);
            hi = std::max(hi, positions[9 * t + 3 * c + a]);
          }
          apart = apart || lo > box[a + 3] || hi < box[a];
        }
        if (!apart) expected.push_back(triangles[t]);
      }
      const uint32_t count = patch.meeting(box, found.data());
      ASSERT_EQ(std::vector<uint32_t>(found.begin(), found.begin() + count), expected)
          << "round " << round << " query " << q;
      met += count;
    }
  }
  EXPECT_GT(met, 400u);  // the queries met something (824 of 800 queries x 96 boxes)
}

}  // namespace
