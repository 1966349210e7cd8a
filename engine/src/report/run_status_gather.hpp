// Gathers a finished run's status (tacta/sim/run_status.hpp) from the haptic loop's counters and
// the collision pipeline's role assignment.
#pragma once

#include "systems/haptic_loop.hpp"
#include "tacta/sim/run_status.hpp"

namespace tacta {

class CollisionContext;

// `collision` may be null (no collision pipeline in the scene).
RunStatus collect_run_status(const HapticLoop& loop, const World& world,
                             const CollisionContext* collision);

}  // namespace tacta
