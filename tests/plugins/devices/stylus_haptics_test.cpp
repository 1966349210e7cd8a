// The real sim_stylus (C ABI) in the loop with the engine's ContactRenderer: the haptic tick as
// the engine runs it (read, render, write), against an analytic tissue plane.
#include <cstdio>
#include <gtest/gtest.h>

#include "../../engine/haptics/analytic_surfaces.hpp"
#include "device_harness.hpp"
#include "tacta/haptics/contact_renderer.hpp"

namespace tacta::testing {
namespace {

using haptics::ContactRenderer;
using haptics::ContactRendererParams;

struct StylusHapticsTest : ::testing::Test {
  LoadedPlugin plugin{"tacta_sim_stylus.so"};
  const tacta_device_api& api = plugin.api<tacta_device_api>("sim_stylus");
  DeviceParams params{plugin.descriptor("sim_stylus")};
  const haptics::testing::PlaneSurface tissue{{0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};

  // Runs `seconds` of 1 kHz ticks; returns the renderer's report numbers, checking every force.
  haptics::ContactStats run(DeviceInstance& device, ContactRendererParams rp, double seconds) {
    rp.peak_force = device.capabilities().peak_force;
    ContactRenderer renderer(rp);
    const tacta_device_sample first = device.read(0.0);
    renderer.reset({first.position[0], first.position[1], first.position[2]});
    const int ticks = static_cast<int>(seconds * 1000.0 + 0.5);
    for (int n = 0; n < ticks; ++n) {
      const double t = n * 1e-3;
      const tacta_device_sample s = device.read(t);
      const auto r = renderer.tick(tissue, t, {s.position[0], s.position[1], s.position[2]},
                                   {s.velocity[0], s.velocity[1], s.velocity[2]}, 1e-3);
      EXPECT_LE(norm(r.device_force), rp.peak_force) << "t = " << t;
      device.write(t, r.device_force[0], r.device_force[1], r.device_force[2]);
    }
    return renderer.stats();
  }
};

TEST_F(StylusHapticsTest, PalpationFeelsTheSteadyForceWithoutAnOnsetSpike) {
  params.number("pattern", 3)
      .vector("palpation_points", {0.0, 0.0, 0.0})
      .number("depth", 0.005)
      .number("approach_height", 0.01)
      .number("travel_duration", 0.0)
      .number("press_duration", 0.4)
      .number("dwell_duration", 1.0);
  DeviceInstance device(api, params.setup());
  ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
  ContactRendererParams rp;
  rp.coupling = {1000.0, 5.0};
  rp.stats.settle_delay = 0.6;  // contact begins mid-press; the dwell holds from 0.4 s to 1.4 s
  const haptics::ContactStats stats = run(device, rp, 1.2);
  std::printf("palpation: first contact %.3f s, peak %.4f N, steady %.4f N, injected %.2e J\n",
              stats.first_contact_time, stats.first_contact_peak, stats.steady_contact,
              stats.energy_injected);
  EXPECT_NEAR(stats.steady_contact, 300.0 * 1000.0 / 1300.0 * 0.005,
              0.01);  // hand and coupling in series
  EXPECT_LE(stats.first_contact_peak, 1.2 * stats.steady_contact);
  EXPECT_LT(stats.energy_injected, 1e-5);
}

// Undamped hand tapping a 3000 N/m wall with no coupling damping: the observer sees the sampled
// wall return more energy than it took unless the controller is on.
TEST_F(StylusHapticsTest, UndampedTapsOnAStiffWallInjectNoEnergyWithTheController) {
  params.number("pattern", 1)
      .vector("tap_point", {0.0, 0.0, 0.0})
      .number("tap_period", 0.25)
      .number("depth", 0.0005)
      .number("approach_height", 0.002)
      .number("hand_damping", 0.0)
      .number("hand_stiffness", 200.0);
  ContactRendererParams rp;
  rp.coupling = {3000.0, 0.0};
  rp.first_contact_enabled = false;
  rp.passivity.controller_enabled = false;
  DeviceInstance open_loop(api, params.setup());
  const haptics::ContactStats without = run(open_loop, rp, 2.0);
  rp.passivity.controller_enabled = true;
  DeviceInstance controlled(api, params.setup());
  const haptics::ContactStats with = run(controlled, rp, 2.0);
  std::printf("stiff wall taps: injected %.3e J without controller, %.3e J with\n",
              without.energy_injected, with.energy_injected);
  EXPECT_GT(without.energy_injected, 1e-4);
  EXPECT_LT(with.energy_injected, 0.01 * without.energy_injected);
}

}  // namespace
}  // namespace tacta::testing
