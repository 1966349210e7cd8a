#include "tacta/haptics/virtual_coupling.hpp"

namespace tacta::haptics {

Vec3 VirtualCoupling::force(const Vec3& stretch, const Vec3& relative_velocity) const noexcept {
  return add(scaled(stretch, params_.stiffness), scaled(relative_velocity, params_.damping));
}

}  // namespace tacta::haptics
