// sim_stylus through the real C ABI: free-space tracking, force saturation, the closed loop
// against a stiff wall, deterministic seeded noise, quantisation and the scripted patterns.
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <vector>

#include "device_harness.hpp"

namespace tacta::testing {
namespace {

constexpr double kTick = 1e-3;  // s

struct SimStylusTest : ::testing::Test {
  LoadedPlugin plugin{"tacta_sim_stylus.so"};
  const tacta_descriptor& descriptor = plugin.descriptor("sim_stylus");
  const tacta_device_api& api = plugin.api<tacta_device_api>("sim_stylus");
  DeviceParams params{descriptor};
};

TEST_F(SimStylusTest, DescriptorIsADeviceWithOmniCapabilities) {
  EXPECT_EQ(descriptor.kind, TACTA_KIND_DEVICE);
  params.vector("workspace_origin", {0.1, 0.2, 0.3});
  DeviceInstance device(api, params.setup());
  ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
  const tacta_device_capabilities c = device.capabilities();
  EXPECT_DOUBLE_EQ(c.peak_force, 3.3);
  EXPECT_DOUBLE_EQ(c.continuous_force, 0.88);
  EXPECT_DOUBLE_EQ(c.usable_stiffness, 1000.0);
  EXPECT_DOUBLE_EQ(c.nominal_rate, 1000.0);
  EXPECT_NEAR(c.workspace_max[0] - c.workspace_min[0], 0.160, 1e-12);
  EXPECT_NEAR(c.workspace_max[1] - c.workspace_min[1], 0.120, 1e-12);
  EXPECT_NEAR(c.workspace_max[2] - c.workspace_min[2], 0.070, 1e-12);
  EXPECT_NEAR(0.5 * (c.workspace_max[2] + c.workspace_min[2]), 0.3, 1e-12);
  EXPECT_EQ(c.dof_out, 3u);
  const tacta_device_sample s = device.read(0.5);  // no waypoints: the hand rests at the origin
  EXPECT_NEAR(s.position[0], 0.1, 1e-12);
  EXPECT_NEAR(s.position[1], 0.2, 1e-12);
  EXPECT_NEAR(s.position[2], 0.3, 1e-12);
}

// Tolerance: with the default critically damped hand (0.1 kg, 300 N/m, 11 N s/m) the tracking
// error of a ramp decays to zero; the corners (a 30 mm/s velocity step) leave under 0.5 mm.
TEST_F(SimStylusTest, FollowsWaypointsInFreeSpace) {
  params.vector("waypoints", {0.0, 0.0, 0.0, 0.0, 1.0, 0.03, 0.0, 0.0, 2.0, 0.03, 0.02, 0.01});
  DeviceInstance device(api, params.setup());
  ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
  double worst = 0.0;
  for (int n = 0; n <= 3000; ++n) {
    const double t = n * kTick;
    tacta_device_sample s{};
    ASSERT_EQ(device.read(t, s), TACTA_DEVICE_CONNECTED);
    const double u = std::clamp(t, 0.0, 1.0), w = std::clamp(t - 1.0, 0.0, 1.0);
    const double target[3] = {0.03 * u, 0.02 * w, 0.01 * w};
    worst = std::max(worst, std::hypot(s.position[0] - target[0], s.position[1] - target[1],
                                       s.position[2] - target[2]));
    if (n == 500) {
      EXPECT_NEAR(s.velocity[0], 0.03, 1e-3);
    }
    if (n == 3000) {
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(s.position[i], target[i], 1e-5);
    }
  }
  EXPECT_LT(worst, 0.5e-3);
  EXPECT_GT(worst, 1e-6);  // the hand is an impedance, not a teleport
}

TEST_F(SimStylusTest, WrittenForceSaturatesAtThePeak) {
  params.number("hand_stiffness", 0.0).number("hand_damping", 0.0).number("hand_mass", 0.1);
  DeviceInstance device(api, params.setup());
  ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
  device.read(0.0);
  device.write(0.0, 100.0, 0.0, 0.0);  // asks for 100 N; the Omni gives 3.3 N
  const tacta_device_sample s = device.read(0.01);
  EXPECT_NEAR(s.velocity[0], 3.3 / 0.1 * 0.01, 1e-9);  // v = F/m t with F = 3.3 N
  device.write(0.01, std::nan(""), 0.0, 0.0);          // a NaN force renders as zero
  const tacta_device_sample after = device.read(0.02);
  EXPECT_NEAR(after.velocity[0], s.velocity[0], 1e-12);
}

// Closed loop: the hand aims 5 mm into a 1000 N/m wall at y = 0; the stylus settles where the
// hand force k_hand (target - y) balances the wall force k_wall (-y).
TEST_F(SimStylusTest, ClosedLoopSettlesWhereHandBalancesWall) {
  const double k_hand = 300.0, k_wall = 1000.0, target = -0.005;
  params.vector("waypoints", {0.0, 0.0, 0.01, 0.0, 0.3, 0.0, target, 0.0})
      .number("hand_stiffness", k_hand);
  DeviceInstance device(api, params.setup());
  ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
  tacta_device_sample s{};
  double force = 0.0;
  for (int n = 0; n <= 3000; ++n) {
    device.read(n * kTick, s);
    force = s.position[1] < 0.0 ? -k_wall * s.position[1] : 0.0;
    device.write(n * kTick, 0.0, force, 0.0);
  }
  const double expected_y = k_hand * target / (k_hand + k_wall);
  EXPECT_NEAR(s.position[1], expected_y, 1e-7);
  EXPECT_NEAR(force, -k_hand * (target - s.position[1]), 1e-4);  // wall up, hand down
  EXPECT_NEAR(force, 1.1538461538, 1e-4);
}

std::vector<double> noisy_run(const tacta_device_api& api, DeviceParams& params, uint64_t seed) {
  DeviceInstance device(api, params.setup(seed));
  std::vector<double> ys;
  for (int n = 0; n < 3000; ++n) ys.push_back(device.read(n * kTick).position[1]);
  return ys;
}

TEST_F(SimStylusTest, SeededNoiseIsDeterministicWithTheRightSpread) {
  params.vector("waypoints", {0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.02, 0.0});
  const std::vector<double> clean = noisy_run(api, params, 42);
  params.number("noise_std", 1e-4);
  const std::vector<double> a = noisy_run(api, params, 42);
  const std::vector<double> b = noisy_run(api, params, 42);
  const std::vector<double> c = noisy_run(api, params, 43);
  EXPECT_EQ(a, b);  // bit for bit
  EXPECT_NE(a, c);
  double sum = 0.0, sum_squares = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    sum += a[i] - clean[i];
    sum_squares += (a[i] - clean[i]) * (a[i] - clean[i]);
  }
  const double mean = sum / a.size();
  const double std_dev = std::sqrt(sum_squares / a.size() - mean * mean);
  EXPECT_NEAR(std_dev, 1e-4, 0.1e-4);  // 3000 samples: the estimate is within ~3 % (1 sigma)
  EXPECT_NEAR(mean, 0.0, 1e-5);
}

TEST_F(SimStylusTest, EncoderQuantisationSnapsToCounts) {
  const double step = 1e-4;
  params.vector("waypoints", {0.0, 0.0, 0.0, 0.0, 1.0, 0.0123, 0.00456, 0.0})
      .number("encoder_resolution", step);
  DeviceInstance device(api, params.setup());
  for (int n = 0; n < 1000; n += 37) {
    const tacta_device_sample s = device.read(n * kTick);
    for (int i = 0; i < 3; ++i)
      EXPECT_NEAR(s.position[i] / step, std::round(s.position[i] / step), 1e-6);
  }
}

TEST_F(SimStylusTest, PalpationPressesEachPointToDepth) {
  params.number("pattern", 3)
      .vector("palpation_points", {0.0, 0.0, 0.0, 0.02, 0.0, 0.01})
      .number("depth", 0.004)
      .number("approach_height", 0.01)
      .number("travel_duration", 0.4)
      .number("press_duration", 0.3)
      .number("dwell_duration", 0.5);
  DeviceInstance device(api, params.setup());
  ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
  tacta_device_sample s{};
  const double block = 0.4 + 0.3 + 0.3 + 0.5;
  for (int n = 0; n <= 3000; ++n) {
    device.read(n * kTick, s);
    if (n == 0) {
      EXPECT_NEAR(s.position[1], 0.01, 1e-9);  // hovering above the first point
    }
    if (n == 1100) {
      EXPECT_NEAR(s.position[1], -0.004, 1e-4);  // end of the first dwell
    }
    if (n == static_cast<int>((block + 1.1) * 1000)) {
      EXPECT_NEAR(s.position[0], 0.02, 1e-4);
      EXPECT_NEAR(s.position[1], -0.004, 1e-4);
      EXPECT_NEAR(s.position[2], 0.01, 1e-4);
    }
  }
}

TEST_F(SimStylusTest, RepeatedPalpationStartsOverAtTheFirstPoint) {
  // Two points, 1.5 s each: the cycle is 3 s. Repeating, the second cycle travels from the last
  // point back to the first and presses it again; without repeat the hand stays above the last.
  for (const bool repeat : {true, false}) {
    params.number("pattern", 3)
        .vector("palpation_points", {0.0, 0.0, 0.0, 0.02, 0.0, 0.01})
        .number("depth", 0.004)
        .number("approach_height", 0.01)
        .number("travel_duration", 0.4)
        .number("press_duration", 0.3)
        .number("dwell_duration", 0.5)
        .number("palpation_repeat", repeat ? 1 : 0);
    DeviceInstance device(api, params.setup());
    ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
    tacta_device_sample s{};
    for (int n = 0; n <= 4100; ++n) {
      device.read(n * kTick, s);
      if (n == 3200) {  // half way back: between the two points, above them
        // Travelling back to the first point, or staying at the last.
        EXPECT_NEAR(s.position[0], repeat ? 0.01 : 0.02, repeat ? 5e-3 : 1e-4) << repeat;
      }
    }
    // 4.1 s is the end of the first point's second dwell.
    EXPECT_NEAR(s.position[0], repeat ? 0.0 : 0.02, 1e-4) << repeat;
    EXPECT_NEAR(s.position[1], repeat ? -0.004 : 0.01, 1e-4) << repeat;
  }
}

TEST_F(SimStylusTest, TapAndStrokePatternsReachTheirPoints) {
  // Tap: top of the stroke at each period start, deepest at half period (raised cosine).
  params.number("pattern", 1)
      .vector("tap_point", {0.01, 0.0, 0.0})
      .number("tap_period", 0.5)
      .number("depth", 0.004)
      .number("approach_height", 0.01);
  {
    DeviceInstance device(api, params.setup());
    ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
    tacta_device_sample s{};
    double lowest = 1.0;
    for (int n = 0; n <= 1000; ++n) {
      device.read(n * kTick, s);
      if (n >= 500) lowest = std::min(lowest, s.position[1]);
    }
    // The hand filters the 2 Hz raised cosine (centre 3 mm, amplitude 7 mm) by
    // |H| = |k + j c w| / |k - m w^2 + j c w| (k 300 N/m, c 11 N s/m, m 0.1 kg, w = 4 pi rad/s).
    const double w = 4.0 * std::numbers::pi;
    const double gain = std::hypot(300.0, 11.0 * w) / std::hypot(300.0 - 0.1 * w * w, 11.0 * w);
    EXPECT_NEAR(lowest, 0.003 - 0.007 * gain, 5e-5);
    EXPECT_NEAR(s.position[1], 0.003 + 0.007 * gain, 5e-5);
    EXPECT_NEAR(s.position[0], 0.01, 1e-9);
  }
  // Stroke: down at the start, along to the end at 20 mm/s, up again.
  params.number("pattern", 2)
      .vector("stroke_start", {0.0, 0.0, 0.0})
      .vector("stroke_end", {0.02, 0.0, 0.0})
      .number("stroke_speed", 0.02);
  DeviceInstance device(api, params.setup());
  ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
  tacta_device_sample s{};
  const double vertical = 0.014 / 0.02;  // s: approach height plus depth at the stroke speed
  for (int n = 0; n <= 3000; ++n) {
    device.read(n * kTick, s);
    if (n == static_cast<int>((vertical + 0.5) * 1000)) {
      EXPECT_NEAR(s.position[0], 0.01, 2e-4);    // half way along
      EXPECT_NEAR(s.position[1], -0.004, 2e-4);  // at depth
    }
  }
  EXPECT_NEAR(s.position[0], 0.02, 1e-5);
  EXPECT_NEAR(s.position[1], 0.01, 1e-5);
}

TEST_F(SimStylusTest, BadScriptIsRefusedAtCreateWithAReason) {
  params.vector("waypoints", {1.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0});
  DeviceInstance device(api, params.setup());
  EXPECT_EQ(device.create_status(), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(device.message().find("waypoint 1"), std::string::npos) << device.message();
}

// button_times: bit 0 is set from each press until its release, whatever the hand does.
TEST_F(SimStylusTest, ButtonHeldFromEachPressUntilItsRelease) {
  params.vector("button_times", {0.1, 0.2, 0.35, 0.5})
      .vector("palpation_points", {0.0, 0.0, 0.0})
      .vector("waypoints", {0.0, 0.0, 0.0, 0.0, 1.0, 0.01, 0.0, 0.0});
  for (int pattern = 0; pattern < 4; ++pattern) {
    SCOPED_TRACE(pattern);
    params.number("pattern", pattern);
    DeviceInstance device(api, params.setup());
    ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
    int held = 0;
    for (int n = 0; n <= 600; ++n) {
      const double t = n * kTick;
      const bool expected = (t >= 0.1 && t < 0.2) || (t >= 0.35 && t < 0.5);
      tacta_device_sample s{};
      device.read(t, s);
      ASSERT_EQ(s.buttons, expected ? 1u : 0u) << "t = " << t << " s";
      held += expected;
    }
    EXPECT_EQ(held, 250);  // 100 + 150 ticks: the windows are half open
  }
  params.vector("button_times", {});
  DeviceInstance plain(api, params.setup());
  EXPECT_EQ(plain.read(0.15).buttons, 0u);  // none by default
}

TEST_F(SimStylusTest, BadButtonTimesAreRefusedAtCreateWithAReason) {
  params.vector("button_times", {0.1, 0.2, 0.3});
  DeviceInstance odd(api, params.setup());
  EXPECT_EQ(odd.create_status(), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(odd.message().find("in pairs"), std::string::npos) << odd.message();
  params.vector("button_times", {0.1, 0.3, 0.2, 0.4});
  DeviceInstance unordered(api, params.setup());
  EXPECT_EQ(unordered.create_status(), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(unordered.message().find("button_times[2]"), std::string::npos) << unordered.message();
}

TEST_F(SimStylusTest, ReportsDisconnected) {
  DeviceInstance device(api, params.setup());
  device.disconnect();
  tacta_device_sample s{};
  EXPECT_EQ(device.read(0.0, s), TACTA_DEVICE_DISCONNECTED);
  std::string reason;
  EXPECT_EQ(device.status(reason), TACTA_DEVICE_DISCONNECTED);
  EXPECT_NE(reason.find("not connected"), std::string::npos);
}

}  // namespace
}  // namespace tacta::testing
