// Virtual coupling (Colgate, Stanley and Brown 1995): a spring and damper between the device
// position and the proxy position. The force it returns acts on the device (what the user feels);
// the reaction, its negative, acts on the proxy and through it on the touched body.
#pragma once

#include "tacta/vec3.hpp"

namespace tacta::haptics {

struct VirtualCouplingParams {
  double stiffness = 500.0;  // N/m; keep below the device's usable stiffness (Omni: ~1000 N/m)
  double damping = 2.0;      // N s/m, on the device-proxy relative velocity
};

class VirtualCoupling {
 public:
  explicit VirtualCoupling(const VirtualCouplingParams& params = {}) noexcept : params_(params) {}

  // Force on the device (N) for a spring stretched by `stretch` = proxy - device (m) and the
  // relative velocity proxy_velocity - device_velocity (m/s).
  Vec3 force(const Vec3& stretch, const Vec3& relative_velocity) const noexcept;
  // Convenience: from positions and velocities.
  Vec3 force(const Vec3& device_position, const Vec3& device_velocity, const Vec3& proxy_position,
             const Vec3& proxy_velocity) const noexcept {
    return force(sub(proxy_position, device_position), sub(proxy_velocity, device_velocity));
  }
  // Energy stored in the spring (J) for a given stretch (m).
  double spring_energy(const Vec3& stretch) const noexcept {
    return 0.5 * params_.stiffness * dot(stretch, stretch);
  }
  const VirtualCouplingParams& params() const noexcept { return params_; }
  void set_params(const VirtualCouplingParams& params) noexcept { params_ = params; }

 private:
  VirtualCouplingParams params_;
};

}  // namespace tacta::haptics
