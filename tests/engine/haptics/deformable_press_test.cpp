// Press and release against elastic tissue, as the liver demo does: the coupling may give the
// device back the energy the device put in (some of it stored in the tissue and returned as the
// tissue springs back), never more. Found in the liver demo (docs/VALIDATION.md, "Haptic
// rendering"): the first-contact stretch limit kept raising the force by time while the device
// was already moving out, so each fast press returned 1.5 times the energy it took.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

#include "analytic_surfaces.hpp"
#include "haptic_chain.hpp"

namespace tacta::haptics::testing {
namespace {

// A flat patch of tissue on a spring: its surface sits at y = -depression, the reaction of the
// coupling pushes it down, its stiffness (N/m) and damping (N s/m) push it back. One degree of
// freedom is enough to store energy and give it back, as the liver does under the stylus.
struct ElasticPatch {
  double mass = 0.02;        // kg, the tissue moving with the contact
  double stiffness = 400.0;  // N/m
  double damping = 0.5;      // N s/m: lightly damped (zeta ~ 0.09), it springs back
  double depression = 0.0;   // m, positive into the tissue
  double rate = 0.0;         // m/s
  PlaneSurface surface{{0.0, 0.0, 0.0}, {0.0, 1.0, 0.0}};

  // body_force: the reaction on the tissue (N), held over the tick as the renderer's output is.
  void step(double dt, const Vec3& body_force, int substeps = 20) {
    const double h = dt / substeps;
    for (int s = 0; s < substeps; ++s) {
      const double push = -body_force[1] - stiffness * depression - damping * rate;
      rate += push / mass * h;
      depression += rate * h;
    }
    surface.set_origin({0.0, -depression, 0.0});
  }
};

// The liver demo's stroke: 12 mm above to 8 mm into the surface in 0.3 s, dwell 0.5 s, back up in
// 0.3 s, with the sim_stylus hand (0.1 kg, 300 N/m, critically damped) and the demo's coupling.
Vec3 palpation_target(double t) {
  const auto smooth = [](double u) {
    u = std::clamp(u, 0.0, 1.0);
    return u * u * (3.0 - 2.0 * u);
  };
  const double down = smooth(t / 0.3), up = smooth((t - 0.8) / 0.3);
  return {0.0, 0.012 - 0.020 * down + 0.020 * up, 0.0};
}

struct PressResult {
  double energy_in = 0.0;   // J, work the device did on the coupling (pushing in)
  double energy_out = 0.0;  // J, work the coupling did on the device (pushing it out)
  ContactStats renderer{};
  double peak_force = 0.0;  // N
};

PressResult press_and_release(double tissue_stiffness, bool rigid) {
  SimulatedHand hand;
  hand.damping = 2.0 * std::sqrt(300.0 * 0.1);
  hand.target = palpation_target;
  hand.position = palpation_target(0.0);
  ElasticPatch patch;
  patch.stiffness = tissue_stiffness;
  ContactRendererParams params;
  params.coupling = {600.0, 1.0};
  ContactRenderer renderer(params);
  renderer.reset(hand.position);
  PressResult result;
  const double dt = 1e-3;
  for (int n = 0; n < 1500; ++n) {
    const ContactRendering r =
        renderer.tick(patch.surface, hand.time, hand.position, hand.velocity, dt);
    const Vec3 before = hand.position;
    hand.step(dt, r.device_force);
    const double work_on_device = dot(r.device_force, sub(hand.position, before));
    (work_on_device > 0.0 ? result.energy_out : result.energy_in) += std::fabs(work_on_device);
    result.peak_force = std::max(result.peak_force, norm(r.device_force));
    if (!rigid) patch.step(dt, r.body_reaction);
  }
  result.renderer = renderer.stats();
  return result;
}

TEST(DeformablePress, ElasticTissueReturnsNoMoreThanTheDevicePutIn) {
  for (double tissue : {200.0, 400.0, 1000.0}) {
    const PressResult r = press_and_release(tissue, false);
    std::printf("tissue %.0f N/m: in %.3e J, out %.3e J, observer deficit %.3e J, peak %.3f N\n",
                tissue, r.energy_in, r.energy_out, r.renderer.energy_injected, r.peak_force);
    EXPECT_GT(r.energy_in, 1e-4) << tissue;  // it really pressed
    // The device gets back what it stored in the coupling and the tissue, less what was lost.
    EXPECT_LE(r.energy_out, r.energy_in + 1e-6) << tissue;
    EXPECT_LE(r.renderer.energy_injected, 1e-6) << tissue;  // J
  }
}

TEST(DeformablePress, RigidWallPressIsPassiveAndKeepsTheOnsetLimit) {
  const PressResult r = press_and_release(0.0, true);
  std::printf(
      "rigid: in %.3e J, out %.3e J, observer deficit %.3e J, onset peak %.3f N, steady %.3f N\n",
      r.energy_in, r.energy_out, r.renderer.energy_injected, r.renderer.first_contact_peak,
      r.renderer.steady_contact);
  EXPECT_LE(r.energy_out, r.energy_in + 1e-6);
  EXPECT_LE(r.renderer.energy_injected, 1e-6);
  EXPECT_GT(r.renderer.steady_contact, 1.0);  // N: the wall is felt (about 1.4 N at the dwell)
  EXPECT_LE(r.renderer.first_contact_peak, 1.2 * r.renderer.steady_contact);
}

}  // namespace
}  // namespace tacta::haptics::testing
