// Passivity: a stiff virtual wall (3000 N/m, no coupling damping) rendered at 1 kHz with a
// zero-order hold is active (Colgate and Schenkel 1997: passive only if b > K T / 2), so an
// undamped hand bouncing on it gains energy. With the passivity controller it must not.
#include <cstdio>
#include <gtest/gtest.h>

#include "analytic_surfaces.hpp"
#include "haptic_chain.hpp"

namespace tacta::haptics::testing {
namespace {

// Undamped hand (0.1 kg, 200 N/m) aiming 1 mm into the wall, released at rest 2 mm above it:
// it bounces on the wall for ever; the energy at release is E0 = 1/2 k (3 mm)^2 = 0.9 mJ.
SimulatedHand bouncing_hand() {
  SimulatedHand hand;
  hand.mass = 0.1;
  hand.stiffness = 200.0;
  hand.damping = 0.0;
  hand.target = [](double) { return Vec3{0.0, -0.001, 0.0}; };
  hand.position = {0.0, 0.002, 0.0};
  return hand;
}

ChainOptions stiff_wall(bool passivity) {
  ChainOptions options;
  options.coupling = {3000.0, 0.0};
  options.first_contact = false;  // the bare wall: nothing else dissipates
  options.passivity = passivity;
  options.peak_force = 1e9;  // no saturation either: the test is about the coupling alone
  return options;
}

TEST(Passivity, StiffWallGainsEnergyWithoutTheController) {
  const PlaneSurface floor({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  SimulatedHand hand = bouncing_hand();
  const double initial = hand.energy();
  EXPECT_NEAR(initial, 0.5 * 200.0 * 0.003 * 0.003, 1e-12);
  const ChainStats stats = run_chain(hand, floor, stiff_wall(false), 2.0);
  std::printf("no controller: E0 %.3e J, after 2 s %.3e J\n", initial, stats.final_energy);
  EXPECT_GT(stats.final_energy, 2.0 * initial);  // the sampled wall pumps energy in
  EXPECT_GT(stats.worst_deficit, initial);       // and the observer sees it
}

TEST(Passivity, StiffWallDoesNotGainEnergyWithTheController) {
  const PlaneSurface floor({0.0, 0.0, 0.0}, {0.0, 1.0, 0.0});
  SimulatedHand hand = bouncing_hand();
  const double initial = hand.energy();
  const ChainStats stats = run_chain(hand, floor, stiff_wall(true), 2.0);
  std::printf("controller: E0 %.3e J, peak %.3e J, after 2 s %.3e J\n", initial, stats.peak_energy,
              stats.final_energy);
  EXPECT_LE(stats.peak_energy, initial * 1.01);  // 1 %: the hold within one tick of a bounce
  EXPECT_LE(stats.final_energy, initial);
  EXPECT_GT(stats.final_energy, 0.5 * initial);  // and not by smothering the contact
}

TEST(Passivity, ObserverSeesAPassiveSpringAsStoredEnergy) {
  // Moving slowly into a 1000 N/m spring and back out: energy in, then the same energy out.
  PassivityController observer({40.0, 1e-6, false});
  observer.reset({0.0, 0.0, 0.0});
  const double k = 1000.0, dt = 1e-3;
  double x = 0.0;
  for (int n = 0; n < 2000; ++n) {
    const double v = n < 1000 ? -0.001 : 0.001;  // m/s: 1 mm in, 1 mm out
    x += v * dt;
    const Vec3 f{0.0, x < 0.0 ? -k * x : 0.0, 0.0};
    observer.update({0.0, x, 0.0}, {0.0, v, 0.0}, dt, f);
    observer.record_sent(f);
    if (n == 999) {
      EXPECT_NEAR(observer.observed_energy(), 0.5 * k * 1e-6, 0.5 * k * 1e-6 * 0.01);
    }
  }
  // Back out, the held force lags one tick, so the sampled spring returns k (v dt)^2 per tick more
  // than it took: -1 uJ over the 1000 ticks. The observer measures exactly that activity.
  EXPECT_NEAR(observer.observed_energy(), -k * 1e-12 * 1000.0, 1e-9);
}

}  // namespace
}  // namespace tacta::haptics::testing
