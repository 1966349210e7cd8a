// Convex plugin (libccd): depth, normal and distance against analytic sphere-sphere and
// sphere-box cases; bad input reported.
#include <cmath>
#include <gtest/gtest.h>

#include "plugin_fixture.hpp"
#include "tacta/collision_api.h"

namespace {

tacta_collision_shape sphere(double x, double y, double z, double r) {
  tacta_collision_shape s{};
  s.type = TACTA_SHAPE_SPHERE;
  s.radius = r;
  s.pose_end = {{x, y, z}, {1, 0, 0, 0}};
  s.pose_start = s.pose_end;
  return s;
}

class ConvexPlugin : public ::testing::Test {
 protected:
  void SetUp() override {
    auto params = tacta::testing::default_params(plugin_.descriptor("convex"));
    tacta_collision_setup setup{sizeof setup, params.data(), static_cast<uint32_t>(params.size()),
                                1e-3};
    char message[256] = {0};
    ASSERT_EQ(api().create(&setup, &instance_, message, sizeof message), TACTA_OK) << message;
  }
  void TearDown() override { api().destroy(instance_); }
  const tacta_collision_api& api() { return plugin_.api<tacta_collision_api>("convex"); }
  tacta::testing::LoadedPlugin plugin_{"tacta_convex.so"};
  void* instance_ = nullptr;
};

TEST_F(ConvexPlugin, SphereSphereDepthAndNormal) {
  const auto a = sphere(0, 0, 0, 1.0), b = sphere(1.5, 0, 0, 1.0);
  tacta_shape_result r{};
  ASSERT_EQ(api().shape_query(instance_, &a, &b, nullptr, &r), 0u);
  ASSERT_EQ(r.intersecting, 1);
  EXPECT_NEAR(r.depth, 0.5, 1e-6);
  EXPECT_NEAR(r.normal[0], -1.0, 1e-6);  // from b towards a
  EXPECT_NEAR(r.normal[1], 0.0, 1e-6);
}

TEST_F(ConvexPlugin, SphereSphereDistanceWhenApart) {
  const auto a = sphere(0, 0, 0, 1.0), b = sphere(0, 3.0, 0, 1.0);
  tacta_shape_result r{};
  ASSERT_EQ(api().shape_query(instance_, &a, &b, nullptr, &r), 0u);
  EXPECT_EQ(r.intersecting, 0);
  EXPECT_NEAR(r.distance, 1.0, 1e-4);  // GJK intersection tolerance limits the bisection
}

TEST_F(ConvexPlugin, SphereBoxFaceDepth) {
  // Unit half-extent box at the origin; sphere of radius 0.5 centred at z = 1.3: depth 0.2.
  tacta_collision_shape box{};
  box.type = TACTA_SHAPE_BOX;
  box.half_extents[0] = box.half_extents[1] = box.half_extents[2] = 1.0;
  box.pose_end = {{0, 0, 0}, {1, 0, 0, 0}};
  const auto s = sphere(0.2, -0.1, 1.3, 0.5);
  tacta_shape_result r{};
  ASSERT_EQ(api().shape_query(instance_, &s, &box, nullptr, &r), 0u);
  ASSERT_EQ(r.intersecting, 1);
  EXPECT_NEAR(r.depth, 0.2, 1e-6);
  EXPECT_NEAR(r.normal[2], 1.0, 1e-6);
}

TEST_F(ConvexPlugin, CapsuleAgainstTriangle) {
  tacta_collision_shape capsule{};
  capsule.type = TACTA_SHAPE_CAPSULE;
  capsule.radius = 0.1;
  capsule.half_length = 0.5;
  capsule.pose_end = {{0.2, 0.2, 0.55}, {1, 0, 0, 0}};  // lower tip at z = -0.05
  const double triangle[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  tacta_shape_result r{};
  ASSERT_EQ(api().shape_query(instance_, &capsule, nullptr, triangle, &r), 0u);
  ASSERT_EQ(r.intersecting, 1);
  EXPECT_NEAR(r.depth, 0.05, 1e-6);
}

TEST_F(ConvexPlugin, BadInputIsReported) {
  auto a = sphere(std::nan(""), 0, 0, 1.0);
  const auto b = sphere(0, 0, 0, 1.0);
  tacta_shape_result r{};
  EXPECT_EQ(api().shape_query(instance_, &a, &b, nullptr, &r),
            static_cast<uint32_t>(TACTA_COLLIDE_NOT_FINITE));
  EXPECT_EQ(api().shape_query(instance_, &b, nullptr, nullptr, &r),
            static_cast<uint32_t>(TACTA_COLLIDE_DEGENERATE));
}

}  // namespace
