// The proxy on a triangle mesh's edge: a collision layer reports the touched face's normal even
// when the closest point is on an edge. A finite-radius proxy placed along that face normal jumps
// sideways by up to 2 r sin(half the bend) as the closest point crosses the edge (seen in the liver
// demo as a proxy flipping by ~1 mm every tick). Placed along the line from the touched point to
// the sphere's centre, it moves continuously.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

#include "tacta/haptics/god_object.hpp"

namespace tacta::haptics::testing {
namespace {

constexpr double kTilt = 15.0 * std::numbers::pi / 180.0;  // rad: a 30 degree bend at the ridge

// Two half-planes meeting at a ridge along z (x = 0, y = 0), each tilted down by `tilt` (rad):
// solid below. Answers like a mesh query: the normal is the touched face's, also on the ridge.
class RidgeSurface : public SurfaceQuery {
 public:
  explicit RidgeSurface(double tilt) : s_(std::sin(tilt)), c_(std::cos(tilt)) {}
  bool first_hit(const Vec3& from, const Vec3& to, double radius,
                 SurfaceHit& hit) const noexcept override {
    double signed_distance = 0.0;
    if (!closest_point(from, 1.0, hit, signed_distance) || signed_distance < radius) return false;
    constexpr int kSamples = 2000;  // a marched sweep is plenty for a test (0.05 % of the sweep)
    for (int i = 1; i <= kSamples; ++i) {
      const double f = static_cast<double>(i) / kSamples;
      const Vec3 centre = add_scaled(from, sub(to, from), f);
      if (closest_point(centre, 1.0, hit, signed_distance) && signed_distance < radius) {
        hit.fraction = f;
        return true;
      }
    }
    return false;
  }
  bool closest_point(const Vec3& p, double max_distance, SurfaceHit& hit,
                     double& signed_distance) const noexcept override {
    // Face k (k = -1 left, +1 right): normal (k s, c, 0), points with k x >= 0 on the plane
    // x s k + y c = 0 ... through the ridge. Distance to each face's half-plane, then the nearer.
    double best = 1e300;
    for (int k : {-1, 1}) {
      const Vec3 n{k * s_, c_, 0.0};
      const double height = dot(p, n);
      Vec3 q = add_scaled(p, n, -height);
      if (k * q[0] < 0.0) q = {0.0, 0.0, p[2]};  // beyond the ridge: the ridge is closest
      const double d = norm(sub(p, q));
      if (d < best) {
        best = d;
        hit.point = q;
        hit.normal = n;
        signed_distance = height >= 0.0 ? d : -d;
      }
    }
    hit.fraction = 0.0;
    return best <= max_distance;
  }

 private:
  double s_, c_;
};

TEST(GodObjectEdges, ProxyCrossesAMeshEdgeWithoutJumping) {
  const RidgeSurface ridge(kTilt);  // as between coarse liver faces
  GodObjectParams params;
  params.radius = 0.004;  // m, the demo's ball tip
  GodObjectProxy proxy(params);
  Vec3 device{-0.01, 0.01, 0.0};
  proxy.reset(device);
  proxy.update(ridge, device, {0.0, 0.0, 0.0});
  ASSERT_FALSE(proxy.in_contact());
  // Press 1 mm into the left face, then slide across the ridge to the right face.
  device = {-0.01, -0.01 * std::tan(kTilt) + 0.004 - 0.001, 0.0};
  proxy.update(ridge, device, {0.0, -0.1, 0.0});
  ASSERT_TRUE(proxy.in_contact());
  double worst_step = 0.0;
  const double step = 1e-4;  // m of device travel per tick
  for (int i = 0; i < 200; ++i) {
    device[0] += step;
    device[1] = -std::abs(device[0]) * std::tan(kTilt) + 0.004 - 0.001;
    const Vec3 before = proxy.position();
    proxy.update(ridge, device, {0.1, 0.0, 0.0});
    ASSERT_TRUE(proxy.in_contact()) << "x " << device[0];
    worst_step = std::max(worst_step, norm(sub(proxy.position(), before)));
  }
  // A continuous proxy moves about as far as the device; the face-normal placement jumped by
  // 2 r sin(15 deg) = 2.1 mm at the ridge.
  EXPECT_LT(worst_step, 3.0 * step);
}

}  // namespace
}  // namespace tacta::haptics::testing
