// First contact: the peak force when a contact begins stays within 1.2 x the steady contact force.
// Hand: 0.1 kg, 300 N/m, critically damped (11 N s/m), as the sim_stylus defaults; coupling
// 1000 N/m (the Omni's usable stiffness) with 5 N s/m.
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

#include "analytic_surfaces.hpp"
#include "haptic_chain.hpp"

namespace tacta::haptics::testing {
namespace {

SimulatedHand default_hand() {
  SimulatedHand hand;
  hand.mass = 0.1;
  hand.stiffness = 300.0;
  hand.damping = 2.0 * std::sqrt(300.0 * 0.1);
  return hand;
}

ChainOptions omni_chain(bool first_contact) {
  ChainOptions options;
  options.coupling = {1000.0, 5.0};
  options.first_contact = first_contact;
  return options;
}

// Steady force: the hand aims 5 mm deep; springs in series give k_hand k / (k_hand + k) * 5 mm.
constexpr double kSteady = 300.0 * 1000.0 / 1300.0 * 0.005;  // N

// The surface arrives under a device that is already 3 mm deep (the body moved onto the tool):
// a coupling that engages at full stretch kicks with 3 N against a 1.15 N steady force.
ChainStats deep_onset(bool first_contact) {
  SimulatedHand hand = default_hand();
  hand.target = [](double) { return Vec3{0.0, -0.005, 0.0}; };
  hand.position = {0.0, -0.003, 0.0};
  const PlaneSurface tissue({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  return run_chain(hand, tissue, omni_chain(first_contact), 3.0);
}

TEST(FirstContact, DeepOnsetWithoutTheLimiterKicks) {
  const ChainStats stats = deep_onset(false);
  std::printf("deep onset, no limiter: peak %.4f N\n", stats.peak_force);
  EXPECT_NEAR(stats.last_force, kSteady, 1e-3);
  EXPECT_GT(stats.peak_force, 2.0 * kSteady);
}

TEST(FirstContact, DeepOnsetPeakStaysWithin1_2TimesSteady) {
  const ChainStats stats = deep_onset(true);
  std::printf("deep onset: peak %.4f N, steady %.4f N, ratio %.3f\n", stats.peak_force,
              stats.last_force, stats.peak_force / stats.last_force);
  EXPECT_NEAR(stats.last_force, kSteady, 1e-3);
  EXPECT_LE(stats.peak_force, 1.2 * stats.last_force);
}

// A palpation press: from 10 mm above to 5 mm deep in `press` seconds (smooth start and stop).
ChainStats press(double press_time) {
  SimulatedHand hand = default_hand();
  hand.target = [press_time](double t) {
    const double u = std::clamp(t / press_time, 0.0, 1.0);
    return Vec3{0.0, 0.01 - 0.015 * u * u * (3.0 - 2.0 * u), 0.0};
  };
  hand.position = {0.0, 0.01, 0.0};
  const PlaneSurface tissue({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  return run_chain(hand, tissue, omni_chain(true), 3.0);
}

TEST(FirstContact, PalpationPressPeakStaysWithin1_2TimesSteady) {
  for (double press_time : {0.3, 0.5, 1.0}) {
    const ChainStats stats = press(press_time);
    std::printf("press %.1f s: peak %.4f N, steady %.4f N, ratio %.3f\n", press_time,
                stats.peak_force, stats.last_force, stats.peak_force / stats.last_force);
    EXPECT_NEAR(stats.last_force, kSteady, 1e-3) << "press " << press_time << " s";
    EXPECT_LE(stats.peak_force, 1.2 * stats.last_force) << "press " << press_time << " s";
  }
}

TEST(FirstContact, LimiterLeavesASlowContactUnchanged) {
  FirstContactLimiter limiter({0.01});
  EXPECT_EQ(limiter.shape({0.0, 0.5, 0.0}, false, 1e-3)[1], 0.5);  // free: untouched
  const Vec3 small{0.0, 5e-6, 0.0};                                // 5 um < 10 um allowed
  EXPECT_EQ(limiter.shape(small, true, 1e-3)[1], small[1]);
  EXPECT_FALSE(limiter.in_onset());
  EXPECT_EQ(limiter.shape({0.0, 0.003, 0.0}, true, 1e-3)[1], 0.003);  // after onset: unchanged
  limiter.shape({0.0, 0.0, 0.0}, false, 1e-3);                        // leave: re-armed
  EXPECT_NEAR(limiter.shape({0.0, 0.003, 0.0}, true, 1e-3)[1], 1e-5, 1e-15);
}

}  // namespace
}  // namespace tacta::haptics::testing

namespace tacta::haptics::testing {
namespace {

// The default stretch rate across the couplings scenes use (600 and 1000 N/m, 0 to 5 N s/m), for
// the liver scene's press (12 mm above to 8 mm deep) in 0.3 s and 0.5 s, and a 3 mm deep onset.
TEST(FirstContact, DefaultRateHoldsAcrossCouplings) {
  const PlaneSurface tissue({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  for (double stiffness : {600.0, 1000.0}) {
    for (double damping : {0.0, 1.0, 5.0}) {
      ChainOptions options;
      options.coupling = {stiffness, damping};
      for (double press_time : {0.3, 0.5}) {
        SimulatedHand hand = default_hand();
        hand.target = [press_time](double t) {
          const double u = std::clamp(t / press_time, 0.0, 1.0);
          return Vec3{0.0, 0.012 - 0.020 * u * u * (3.0 - 2.0 * u), 0.0};
        };
        hand.position = {0.0, 0.012, 0.0};
        const ChainStats stats = run_chain(hand, tissue, options, 2.0);
        EXPECT_LE(stats.peak_force, 1.2 * stats.last_force)
            << "k " << stiffness << " b " << damping << " press " << press_time;
      }
      SimulatedHand deep = default_hand();
      deep.target = [](double) { return Vec3{0.0, -0.005, 0.0}; };
      deep.position = {0.0, -0.003, 0.0};
      const ChainStats stats = run_chain(deep, tissue, options, 3.0);
      EXPECT_LE(stats.peak_force, 1.2 * stats.last_force)
          << "deep, k " << stiffness << " b " << damping;
    }
  }
}

}  // namespace
}  // namespace tacta::haptics::testing
