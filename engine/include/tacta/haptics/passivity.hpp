// Passivity observer and controller at the coupling port (after Hannaford and Ryu, "Time-domain
// passivity control of haptic interfaces", IEEE Trans. Robotics and Automation 18(1), 2002).
//
// Observer: the energy that has flowed from the device into the virtual environment (J),
//   E(n) = E(n-1) - f(n-1) . (x(n) - x(n-1)),
// where f(n-1) is the force actually sent at the previous tick (held constant by the device for
// the whole tick) and x the measured device position. This is the exact work of the held force
// on the device, so sampling and hold effects (the usual source of active virtual walls) show up
// in E. A passive environment keeps E >= 0 at all times.
// Controller: before sending f(n), it predicts E(n+1) ~ E(n) - f(n) . v(n) dt; if that would be
// negative, it adds a damper -alpha v(n) with alpha = -E_pred / (|v|^2 dt), just enough to bring
// the prediction back to zero, capped at max_damping (a discrete damper b is itself stable only
// for b < 2 m / dt on a device of mass m). Any energy the coupling would inject is dissipated.
#pragma once

#include "tacta/vec3.hpp"

namespace tacta::haptics {

struct PassivityParams {
  double max_damping = 40.0;       // N s/m, cap on the adaptive damper
  double min_speed = 1e-6;         // m/s, below this no damper is added (alpha would blow up)
  bool controller_enabled = true;  // false: observe only (for comparisons and tests)
};

class PassivityController {
 public:
  explicit PassivityController(const PassivityParams& params = {}) noexcept : params_(params) {}

  // Starts observing at device position (m); clears the energy.
  void reset(const Vec3& device_position) noexcept;

  // One tick: measured device position (m) and velocity (m/s), tick dt (s), and the force the
  // environment wants to send (N). Returns the force to send (before peak limiting).
  // control = false: observe only this tick (e.g. out of contact, where a damper would be drag).
  Vec3 update(const Vec3& device_position, const Vec3& device_velocity, double dt,
              const Vec3& desired_force, bool control = true) noexcept;

  // The force really sent this tick (after limiting), so the next observation uses it.
  void record_sent(const Vec3& force) noexcept { last_sent_ = force; }

  double observed_energy() const noexcept { return energy_; }              // J, >= 0 when passive
  double worst_energy_deficit() const noexcept { return worst_deficit_; }  // J, max of -E seen
  double dissipated_energy() const noexcept { return dissipated_; }  // J, predicted, by the damper
  double last_damping() const noexcept { return last_alpha_; }       // N s/m

 private:
  PassivityParams params_;
  Vec3 last_position_{0.0, 0.0, 0.0};
  Vec3 last_sent_{0.0, 0.0, 0.0};
  bool started_ = false;
  double energy_ = 0.0;
  double worst_deficit_ = 0.0;
  double dissipated_ = 0.0;
  double last_alpha_ = 0.0;
};

}  // namespace tacta::haptics
