// ProxyPatch's bookkeeping: a query is answered from the patch only while its box lies inside
// the gathered cube shrunk by how far the surface's odometer advanced since; the next cube holds
// the queries served; a gather that held too many triangles is not tried again for as large a
// query for a while, twice as long after each further failure in a row (one a pass), until a
// query of that size fits or the surface changes.
#include <cmath>
#include <gtest/gtest.h>
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

}  // namespace
