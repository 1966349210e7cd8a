// Virtual coupling force and the device force limit.
#include <cmath>
#include <gtest/gtest.h>
#include <limits>

#include "tacta/haptics/force_limiter.hpp"
#include "tacta/haptics/virtual_coupling.hpp"

namespace tacta::haptics {
namespace {

TEST(VirtualCoupling, SpringAndDamperBetweenDeviceAndProxy) {
  const VirtualCoupling coupling({800.0, 3.0});
  const Vec3 f =
      coupling.force({0.0, -0.002, 0.0}, {0.0, 0.1, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(f[1], 800.0 * 0.002 + 3.0 * -0.1);  // pulls the device up to the proxy, damped
  EXPECT_DOUBLE_EQ(f[0], 0.0);
  EXPECT_DOUBLE_EQ(coupling.spring_energy({0.0, 0.002, 0.0}), 0.5 * 800.0 * 4e-6);
}

TEST(ForceLimiter, NeverAboveThePeakKeepsDirectionZeroesNaN) {
  const ForceLimiter limiter(3.3);
  ForceLimitResult result{};
  const Vec3 small = limiter.limit({1.0, -2.0, 0.5}, &result);
  EXPECT_EQ(result, ForceLimitResult::unchanged);
  EXPECT_EQ(small[1], -2.0);
  for (double scale : {1.0, 10.0, 1e3, 1e300}) {
    const Vec3 in{3.0 * scale, -4.0 * scale, 12.0 * scale};  // |in| = 13 scale
    const Vec3 out = limiter.limit(in, &result);
    EXPECT_LE(norm(out), 3.3);
    EXPECT_NEAR(norm(out), 3.3, 1e-9);
    EXPECT_NEAR(out[0] / out[2], 0.25, 1e-12);
  }
  const Vec3 nan = limiter.limit({std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0}, &result);
  EXPECT_EQ(result, ForceLimitResult::non_finite_zeroed);
  EXPECT_EQ(norm(nan), 0.0);
  EXPECT_EQ(norm(limiter.limit({std::numeric_limits<double>::infinity(), 0.0, 0.0})), 0.0);
}

}  // namespace
}  // namespace tacta::haptics
