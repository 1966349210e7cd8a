// Screen <-> world for the viewer's mouse, against hand-computed pinhole geometry.
#include <cmath>
#include <gtest/gtest.h>

#include "camera_ray.hpp"

namespace tacta::view {
namespace {

Camera looking_down_z() {
  Camera c;
  c.eye = {0, 0, 1};
  c.target = {0, 0, 0};
  c.up = {0, 1, 0};
  c.vertical_fov_rad = 0.7;
  return c;
}

TEST(CameraRay, CentrePixelLooksAlongTheViewDirection) {
  const Ray r = pixel_ray(looking_down_z(), {800, 600}, 400, 300);
  EXPECT_NEAR(r.direction[0], 0, 1e-12);
  EXPECT_NEAR(r.direction[1], 0, 1e-12);
  EXPECT_NEAR(r.direction[2], -1, 1e-12);
}

TEST(CameraRay, TopEdgeIsHalfTheVerticalFieldOfViewUp) {
  const Ray r = pixel_ray(looking_down_z(), {800, 600}, 400, 0);
  EXPECT_NEAR(std::atan2(r.direction[1], -r.direction[2]), 0.35, 1e-12);
  const Ray right = pixel_ray(looking_down_z(), {800, 600}, 800, 300);  // aspect 4:3
  EXPECT_NEAR(right.direction[0] / -right.direction[2], std::tan(0.35) * 800.0 / 600.0, 1e-12);
}

TEST(CameraRay, ProjectInvertsThePixelRay) {
  Camera c;
  c.eye = {0.3, 0.25, 0.45};
  c.target = {0.01, 0.02, -0.03};
  for (const auto& [x, y] : {std::pair{10.0, 20.0}, {640.0, 50.0}, {333.0, 477.0}}) {
    const Ray r = pixel_ray(c, {800, 600}, x, y);
    const Vec3d p{r.origin[0] + 0.4 * r.direction[0], r.origin[1] + 0.4 * r.direction[1],
                  r.origin[2] + 0.4 * r.direction[2]};
    const auto px = project(c, {800, 600}, p);
    ASSERT_TRUE(px.has_value());
    EXPECT_NEAR((*px)[0], x, 1e-9);
    EXPECT_NEAR((*px)[1], y, 1e-9);
  }
  EXPECT_FALSE(project(c, {800, 600}, {0.6, 0.5, 0.9}).has_value());  // behind the eye
}

TEST(CameraRay, FacingPlaneKeepsTheDepth) {
  const Camera c = looking_down_z();
  const Vec3d anchor{0, 0, -0.2};
  const auto hit =
      intersect_facing_plane(pixel_ray(c, {800, 600}, 400, 150), anchor, camera_forward(c));
  ASSERT_TRUE(hit.has_value());
  EXPECT_NEAR((*hit)[2], -0.2, 1e-12);
  EXPECT_NEAR((*hit)[1], 1.2 * std::tan(0.35) * 0.5, 1e-12);  // a quarter height up, 1.2 m away
  EXPECT_FALSE(
      intersect_facing_plane({{0, 0, 1}, {1, 0, 0}}, anchor, {0, 0, -1}).has_value());  // parallel
}

}  // namespace
}  // namespace tacta::view
