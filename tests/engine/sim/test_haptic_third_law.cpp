// Newton's third law in haptic contact: every tick the stylus touches the cube, the contact
// forces the haptic interaction puts on the body's nodes add up to minus the force sent to the
// device (the reaction goes to the touched triangle's nodes by barycentric weights). Driven tick
// by tick through World + CollisionContext + HapticInteraction + HapticLoop.
#include <cmath>

#include "sim_test_support.hpp"

namespace tacta::simtest {
namespace {

TEST(HapticContact, BodyReactionIsMinusTheDeviceForceEveryContactTick) {
  const SceneDesc scene = scene_from_text(kCubePressScene, "third_law");
  LoopHarness h(scene, 400);
  ASSERT_EQ(h.world.device_count(), 1u);
  int contact_ticks = 0, ticks_with_force = 0;
  double worst_mismatch_N = 0, largest_force_N = 0;
  for (int k = 0; k < 400; ++k) {
    h.tick();
    const DeviceComponents dev = h.world.device(0);
    const SoftBody body = h.world.body(0);
    double sum[3] = {0, 0, 0};
    for (size_t n = 0; n < body.node_count(); ++n)
      for (int a = 0; a < 3; ++a)
        sum[a] += body.loads.contact_forces[3 * n + static_cast<size_t>(a)];
    const double f_norm = std::sqrt(dev.contact.force[0] * dev.contact.force[0] +
                                    dev.contact.force[1] * dev.contact.force[1] +
                                    dev.contact.force[2] * dev.contact.force[2]);
    if (!dev.contact.in_contact) {
      // Out of contact: no force either way.
      EXPECT_EQ(f_norm, 0.0) << "tick " << k;
      EXPECT_EQ(std::fabs(sum[0]) + std::fabs(sum[1]) + std::fabs(sum[2]), 0.0) << "tick " << k;
      continue;
    }
    ++contact_ticks;
    if (f_norm > 1e-3) ++ticks_with_force;
    largest_force_N = std::max(largest_force_N, f_norm);
    double mismatch = 0;
    for (int a = 0; a < 3; ++a)
      mismatch = std::max(mismatch, std::fabs(sum[a] + dev.contact.force[static_cast<size_t>(a)]));
    worst_mismatch_N = std::max(worst_mismatch_N, mismatch);
    EXPECT_LE(mismatch, 1e-12 * std::max(1.0, f_norm))
        << "tick " << k << ": body got " << sum[0] << ", " << sum[1] << ", " << sum[2]
        << " N, device " << dev.contact.force[0] << ", " << dev.contact.force[1] << ", "
        << dev.contact.force[2] << " N";
  }
  // The scene must actually press: a long contact with a force well above zero.
  EXPECT_GE(contact_ticks, 150);
  EXPECT_GE(ticks_with_force, 100);
  EXPECT_GT(largest_force_N, 0.5);
  RecordProperty("contact_ticks", contact_ticks);
  RecordProperty("largest_force_N", std::to_string(largest_force_N));
  RecordProperty("worst_mismatch_N", std::to_string(worst_mismatch_N));
  // The force pushes the tool up, out of the top face (+y), and the body down.
  EXPECT_GT(h.world.device(0).contact.force[1], 0.0);
}

}  // namespace
}  // namespace tacta::simtest
