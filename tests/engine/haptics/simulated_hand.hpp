// A physical stylus for haptic tests: a point mass (kg) pulled by a hand spring (N/m) and damper
// (N s/m) toward a target, plus the device force held constant over each tick (zero-order hold,
// as a real amplifier), integrated in fine semi-implicit sub-steps. Its mechanical energy tells
// whether the rendering injected energy.
#pragma once

#include <functional>

#include "tacta/vec3.hpp"

namespace tacta::haptics::testing {

struct SimulatedHand {
  double mass = 0.1;         // kg
  double stiffness = 300.0;  // N/m
  double damping = 0.0;      // N s/m, on the velocity relative to the target
  std::function<Vec3(double)> target = [](double) { return Vec3{0.0, 0.0, 0.0}; };
  Vec3 position{0.0, 0.0, 0.0};
  Vec3 velocity{0.0, 0.0, 0.0};
  double time = 0.0;

  void step(double dt, const Vec3& device_force, int substeps = 20) {
    const double h = dt / substeps;
    for (int s = 0; s < substeps; ++s) {
      const Vec3 before = target(time);
      time += h;
      const Vec3 goal = target(time);
      const Vec3 goal_velocity = scaled(sub(goal, before), 1.0 / h);
      const Vec3 hand = add(scaled(sub(goal, position), stiffness),
                            scaled(sub(goal_velocity, velocity), damping));
      velocity = add_scaled(velocity, add(hand, device_force), h / mass);
      position = add_scaled(position, velocity, h);
    }
  }
  // J: kinetic plus the hand spring's energy (target held fixed).
  double energy() const {
    const Vec3 stretch = sub(target(time), position);
    return 0.5 * mass * dot(velocity, velocity) + 0.5 * stiffness * dot(stretch, stretch);
  }
};

}  // namespace tacta::haptics::testing
