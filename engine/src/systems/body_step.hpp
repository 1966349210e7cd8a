// One model step of one body, shared by the two places a body can step: the haptic thread (every
// tick, or at its own slower rate) and a body worker thread (BodyWorker). Builds the external
// forces (gravity plus contact), keeps the start-of-step positions, steps, and checks the result
// (model fault bits, non-finite state, displacement past the divergence limit). On a fault the
// state is put back to the start of the step with zero velocity: the body freezes there.
// noexcept and allocation-free: it runs in the 1 kHz path.
#pragma once

#include <cstdint>
#include <span>

#include "boundary/boundary_motion.hpp"
#include "plugin/plugin_instance.hpp"
#include "tacta/scene.hpp"
#include "world/soft_body.hpp"

namespace tacta {

// The node arrays a step reads and writes (3 doubles per node each).
struct StepArrays {
  std::span<double> positions;        // m
  std::span<double> velocities;       // m/s
  std::span<double> external_forces;  // N, rebuilt here: m g + contact
  std::span<double> step_start;       // m, start of the step
  std::span<const double> contact;    // N per node, what collision and haptics applied
};

struct StepOutcome {
  uint32_t bits = 0;            // the model's TACTA_STEP_* bits, or ours for a caught fault
  const char* why = nullptr;    // non-null when the step faulted
  double max_displacement = 0;  // m from rest, after the step (0 when it faulted)
};

// `boundary` (may be null) moves the body's prescribed and plate-pressed nodes around the step.
StepOutcome step_body_arrays(ModelInstance& model, const BodyTopology& topology,
                             const Vec3& gravity, double divergence_limit_m,
                             const StepArrays& arrays, double time, double dt,
                             BoundaryMotion* boundary = nullptr) noexcept;

}  // namespace tacta
