// God-object proxy against an analytic plane and an analytic sphere.
#include "tacta/haptics/god_object.hpp"

#include <cmath>
#include <gtest/gtest.h>

#include "analytic_surfaces.hpp"

namespace tacta::haptics::testing {
namespace {

constexpr Vec3 kZero{0.0, 0.0, 0.0};

TEST(GodObject, FollowsTheDeviceInFreeSpace) {
  const PlaneSurface floor({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  GodObjectProxy proxy;
  proxy.reset({0.0, 0.05, 0.0});
  proxy.update(floor, {0.01, 0.02, -0.01}, {1.0, 0.0, 0.0});
  EXPECT_FALSE(proxy.in_contact());
  EXPECT_EQ(proxy.position()[0], 0.01);
  EXPECT_EQ(proxy.velocity()[0], 1.0);
}

TEST(GodObject, StaysOnAPlaneAboveTheDeviceAndSlides) {
  const PlaneSurface floor({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  GodObjectParams params;
  params.radius = 0.001;
  GodObjectProxy proxy(params);
  proxy.reset({0.0, 0.01, 0.0});
  // One tick straight through the floor to 5 cm below: no tunnelling.
  proxy.update(floor, {0.0, -0.05, 0.0}, kZero);
  ASSERT_TRUE(proxy.in_contact());
  EXPECT_NEAR(proxy.position()[1], 0.001, 1e-5);
  EXPECT_NEAR(proxy.contact().normal[1], 1.0, 1e-12);
  // Sliding under the surface: the proxy is the device projected on the surface (plus radius).
  for (int n = 1; n <= 20; ++n)
    proxy.update(floor, {0.001 * n, -0.004, 0.002 * n}, {1.0, -0.1, 2.0});
  EXPECT_TRUE(proxy.in_contact());
  EXPECT_NEAR(proxy.position()[0], 0.02, 1e-12);
  EXPECT_NEAR(proxy.position()[2], 0.04, 1e-12);
  EXPECT_NEAR(proxy.position()[1], 0.001 + params.skin, 1e-12);
  EXPECT_NEAR(proxy.velocity()[1], 0.0, 1e-12);  // tangential only
  EXPECT_NEAR(proxy.velocity()[0], 1.0, 1e-12);
  // Lifting the device out releases the contact.
  proxy.update(floor, {0.02, 0.01, 0.04}, kZero);
  EXPECT_FALSE(proxy.in_contact());
  EXPECT_EQ(proxy.position()[1], 0.01);
}

TEST(GodObject, ProxyFindsASurfaceThatArrivedOverTheDevice) {
  const PlaneSurface floor({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  GodObjectProxy proxy;
  proxy.reset({0.003, -0.002, 0.0});  // already 2 mm inside
  proxy.update(floor, {0.003, -0.002, 0.0}, kZero);
  ASSERT_TRUE(proxy.in_contact());
  EXPECT_NEAR(proxy.position()[1], 0.0, 1e-5);
  EXPECT_NEAR(proxy.position()[0], 0.003, 1e-12);
}

TEST(GodObject, StaysOnASphereAtTheDevicesRadialProjection) {
  const Vec3 centre{0.01, 0.02, -0.01};
  const double radius = 0.03;
  const SphereSurface ball(centre, radius);
  GodObjectProxy proxy;
  proxy.reset(add(centre, {0.0, 0.05, 0.0}));  // above the ball
  // The device sinks into the ball off-axis, then moves around inside it.
  const Vec3 direction = scaled(Vec3{0.3, 1.0, 0.2}, 1.0 / norm(Vec3{0.3, 1.0, 0.2}));
  Vec3 device = add_scaled(centre, direction, radius - 0.004);
  for (int n = 0; n < 50; ++n) proxy.update(ball, device, kZero);
  ASSERT_TRUE(proxy.in_contact());
  const Vec3 expected = add_scaled(centre, direction, radius);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(proxy.position()[i], expected[i], 2e-6);
  // Sweep the device around inside the ball: the proxy stays on the surface all the way.
  double worst_off_surface = 0.0;
  for (int n = 0; n <= 200; ++n) {
    const double a = 0.005 * n;
    const Vec3 d{std::sin(a) * 0.6, std::cos(a), 0.2};
    device = add_scaled(centre, scaled(d, 1.0 / norm(d)), radius - 0.003);
    proxy.update(ball, device, kZero);
    ASSERT_TRUE(proxy.in_contact());
    worst_off_surface =
        std::max(worst_off_surface, std::abs(norm(sub(proxy.position(), centre)) - radius));
  }
  EXPECT_LT(worst_off_surface, 2e-6);
  const Vec3 last_direction = scaled(sub(device, centre), 1.0 / norm(sub(device, centre)));
  const Vec3 proxy_direction = scaled(sub(proxy.position(), centre), 1.0 / radius);
  EXPECT_GT(dot(last_direction, proxy_direction), std::cos(0.01));  // within 10 mrad
}

}  // namespace
}  // namespace tacta::haptics::testing
