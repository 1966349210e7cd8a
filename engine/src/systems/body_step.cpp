#include "systems/body_step.hpp"

#include <algorithm>
#include <cmath>

namespace tacta {

namespace {

bool all_finite(std::span<const double> x) noexcept {
  for (double v : x)
    if (!std::isfinite(v)) return false;
  return true;
}

}  // namespace

StepOutcome step_body_arrays(ModelInstance& model, const BodyTopology& topology,
                             const Vec3& gravity, double divergence_limit_m, const StepArrays& a,
                             double time, double dt, BoundaryMotion* boundary) noexcept {
  const std::vector<double>& m = topology.masses;
  const std::vector<double>& rest = topology.mesh.positions;
  for (size_t n = 0; n < m.size(); ++n)
    for (size_t k = 0; k < 3; ++k)
      a.external_forces[3 * n + k] = m[n] * gravity[k] + a.contact[3 * n + k];
  if (boundary != nullptr) boundary->before_step(a.positions, a.velocities, time);
  std::copy(a.positions.begin(), a.positions.end(), a.step_start.begin());
  tacta_body_state state{static_cast<uint32_t>(m.size()), a.positions.data(), a.velocities.data(),
                         a.external_forces.data(), time};
  StepOutcome out;
  out.bits = model.step(state, dt);
  if (boundary != nullptr && !(out.bits & TACTA_STEP_FAULT_MASK))
    boundary->after_step(model, a.positions, a.velocities, a.external_forces, time, dt);
  if (out.bits & TACTA_STEP_FAULT_MASK) {
    out.why = "the model reported a fault";
  } else if (!all_finite(a.positions) || !all_finite(a.velocities)) {
    out.bits = TACTA_STEP_NOT_FINITE;
    out.why = "NaN or infinity in the node state";
  } else {
    double max_d2 = 0;
    for (size_t i = 0; i < rest.size(); i += 3) {
      const double dx = a.positions[i] - rest[i], dy = a.positions[i + 1] - rest[i + 1],
                   dz = a.positions[i + 2] - rest[i + 2];
      max_d2 = std::max(max_d2, dx * dx + dy * dy + dz * dz);
    }
    out.max_displacement = std::sqrt(max_d2);
    if (out.max_displacement > divergence_limit_m) {
      out.bits = TACTA_STEP_DIVERGED;
      out.why = "displacement exceeded ten body sizes";
    }
  }
  if (out.why != nullptr) {
    // Frozen at the start of the step: the last state that could be trusted.
    std::copy(a.step_start.begin(), a.step_start.end(), a.positions.begin());
    std::fill(a.velocities.begin(), a.velocities.end(), 0.0);
    out.max_displacement = 0;
  }
  return out;
}

}  // namespace tacta
