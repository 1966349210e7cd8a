// The ContactRenderer as the haptic task uses it: Newton's third law, the force limit, bad
// samples, and the per-device report numbers.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <limits>

#include "analytic_surfaces.hpp"
#include "haptic_chain.hpp"

namespace tacta::haptics::testing {
namespace {

TEST(ContactRenderer, ReactionOnTheBodyIsMinusTheDeviceForceAtTheContactPoint) {
  const SphereSurface ball({0.0, 0.0, 0.0}, 0.05);
  ContactRendererParams params;
  params.coupling = {800.0, 2.0};
  params.first_contact_enabled = false;
  ContactRenderer renderer(params);
  renderer.reset({0.0, 0.08, 0.0});
  renderer.tick(ball, 0.0, {0.0, 0.08, 0.0}, {0.0, 0.0, 0.0}, 1e-3);
  const ContactRendering r =
      renderer.tick(ball, 1e-3, {0.001, 0.048, 0.0}, {0.0, -0.01, 0.0}, 1e-3);
  ASSERT_TRUE(r.in_contact);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(r.body_reaction[i], -r.device_force[i]);
  EXPECT_GT(r.device_force[1], 0.0);                // pushes the device out of the ball
  EXPECT_NEAR(norm(r.contact.point), 0.05, 1e-12);  // on the surface
  EXPECT_NEAR(r.device_force[1], 800.0 * 0.002 + 2.0 * 0.01, 2e-2);  // ~k depth + b v
}

TEST(ContactRenderer, DeviceForceNeverExceedsThePeak) {
  // A hand driving 30 mm into a 3000 N/m wall asks for up to ~90 N; the Omni gives 3.3 N.
  SimulatedHand hand;
  hand.stiffness = 2000.0;
  hand.damping = 2.0 * std::sqrt(2000.0 * 0.1);
  hand.target = [](double t) { return Vec3{0.0, 0.01 - 0.04 * std::min(t / 0.2, 1.0), 0.0}; };
  hand.position = {0.0, 0.01, 0.0};
  const PlaneSurface wall({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  ChainOptions options;
  options.coupling = {3000.0, 2.0};
  const ChainStats stats = run_chain(hand, wall, options, 1.0);
  EXPECT_LE(stats.peak_force, 3.3);
  EXPECT_NEAR(stats.peak_force, 3.3, 1e-6);  // it did saturate
  EXPECT_GT(stats.renderer.limited_forces, 0u);
  EXPECT_EQ(stats.renderer.max_force, stats.peak_force);
  EXPECT_EQ(stats.renderer.force_limit, 3.3);
}

TEST(ContactRenderer, NonFiniteSampleGivesZeroForceTheSameTick) {
  const PlaneSurface wall({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  ContactRenderer renderer;
  renderer.reset({0.0, 0.001, 0.0});
  renderer.tick(wall, 0.0, {0.0, 0.001, 0.0}, {0.0, 0.0, 0.0}, 1e-3);
  const ContactRendering in = renderer.tick(wall, 1e-3, {0.0, -0.002, 0.0}, {0.0, -0.1, 0.0}, 1e-3);
  EXPECT_GT(norm(in.device_force), 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const ContactRendering bad = renderer.tick(wall, 2e-3, {nan, -0.002, 0.0}, {0.0, 0.0, 0.0}, 1e-3);
  EXPECT_EQ(norm(bad.device_force), 0.0);
  EXPECT_EQ(renderer.stats().non_finite_forces, 1u);
}

TEST(ContactRenderer, ReportsFirstContactPeakSteadyForceAndInjectedEnergy) {
  SimulatedHand hand;
  hand.damping = 2.0 * std::sqrt(300.0 * 0.1);
  hand.target = [](double t) {
    const double u = std::clamp(t / 0.5, 0.0, 1.0);
    return Vec3{0.0, 0.01 - 0.015 * u * u * (3.0 - 2.0 * u), 0.0};
  };
  hand.position = {0.0, 0.01, 0.0};
  const PlaneSurface tissue({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  ChainOptions options;
  options.coupling = {1000.0, 5.0};
  const ChainStats stats = run_chain(hand, tissue, options, 2.0);
  const ContactStats& r = stats.renderer;
  EXPECT_GT(r.first_contact_time, 0.2);  // the target crosses the surface at t = 0.5 * 0.6 s
  EXPECT_LT(r.first_contact_time, 0.4);
  EXPECT_NEAR(r.steady_contact, 300.0 * 1000.0 / 1300.0 * 0.005, 0.02);
  EXPECT_LE(r.first_contact_peak, 1.2 * r.steady_contact);
  EXPECT_GE(r.energy_injected, 0.0);
  EXPECT_LT(r.energy_injected, 1e-5);  // J: the controller keeps it near zero
}

}  // namespace
}  // namespace tacta::haptics::testing

namespace tacta::haptics::testing {
namespace {

// Pressed 2 mm into a wall, then pulled out at 0.2 m/s: the coupling damper (5 N s/m) on the
// relative velocity would pull with up to 1 N as the spring relaxes. A contact only pushes.
TEST(ContactRenderer, NeverPullsTheDeviceIntoTheSurfaceOnRelease) {
  const PlaneSurface wall({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  ContactRendererParams params;
  params.coupling = {600.0, 5.0};
  params.first_contact_enabled = false;
  ContactRenderer renderer(params);
  Vec3 device{0.0, 0.001, 0.0};
  renderer.reset(device);
  double least_normal_force = 0.0;
  int contact_ticks = 0;
  for (int n = 0; n < 60; ++n) {
    const double speed = n < 15 ? -0.2 : 0.2;  // m/s along y: 3 mm in, then out
    device[1] += speed * 1e-3;
    const ContactRendering r = renderer.tick(wall, n * 1e-3, device, {0.0, speed, 0.0}, 1e-3);
    if (r.in_contact) ++contact_ticks;
    least_normal_force = std::min(least_normal_force, r.device_force[1]);
  }
  EXPECT_GT(contact_ticks, 10);
  EXPECT_GE(least_normal_force, 0.0);
}

}  // namespace
}  // namespace tacta::haptics::testing

namespace tacta::haptics::testing {
namespace {

// A host that zeroes the force after tick() (a fault) reports it; the observer then integrates
// zero work for the device's motion over that tick instead of the force it never got.
TEST(ContactRenderer, ObserverIntegratesTheForceTheHostReallySent) {
  const PlaneSurface wall({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  ContactRendererParams params;
  params.first_contact_enabled = false;
  ContactRenderer renderer(params);
  renderer.reset({0.0, 0.001, 0.0});
  renderer.tick(wall, 0.0, {0.0, -0.001, 0.0}, {0.0, 0.0, 0.0}, 1e-3);
  const ContactRendering r = renderer.tick(wall, 1e-3, {0.0, -0.002, 0.0}, {0.0, 0.0, 0.0}, 1e-3);
  ASSERT_GT(r.device_force[1], 0.0);
  renderer.override_sent({0.0, 0.0, 0.0});
  const double before = renderer.passivity().observed_energy();
  renderer.tick(wall, 2e-3, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0},
                1e-3);  // moved out 2 mm under no force
  EXPECT_EQ(renderer.passivity().observed_energy(), before);
}

}  // namespace
}  // namespace tacta::haptics::testing
