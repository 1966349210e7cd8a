// The individual conformance checks. Each builds what it needs from the descriptor (a fresh
// instance on a fresh body, so no check sees another's history) and may throw InputError when
// the plugin refuses the body; suite.cpp turns that into a failed check.
#pragma once

#include "tacta/conformance.hpp"

namespace tacta::conformance {

// Of E h^2 (the test cube's force figure): what round-off leaves at rest and under rigid motion
// (the in-tree models stay below 1e-15 of it).
constexpr double kForceRoundOff = 1e-9;

CheckResult check_schema(const tacta_descriptor& model);

CheckResult check_force_at_rest(const tacta_descriptor& model);
CheckResult check_stretch_response(const tacta_descriptor& model);
CheckResult check_rigid_translation(const tacta_descriptor& model);
CheckResult check_rigid_rotation(const tacta_descriptor& model);
CheckResult check_net_force(const tacta_descriptor& model);

CheckResult check_step_allocations(const tacta_descriptor& model, const AllocationProbe& probe);
CheckResult check_nan_reported(const tacta_descriptor& model);
CheckResult check_worker_thread(const tacta_descriptor& model);
CheckResult check_live_params(const tacta_descriptor& model);
// save_state/load_state restore bit for bit (or NO_HISTORY is claimed); bad blobs are refused.
CheckResult check_checkpoint(const tacta_descriptor& model);

// With TACTA_MODEL_CLAIM_TOPOLOGY_EDITS: a fresh instance on a cut cube, warm-started from the
// old state, is at rest at its rest shape, stays finite and gains no energy.
CheckResult check_topology_edits(const tacta_descriptor& model);

// The descriptor's TACTA_MODEL_CLAIM_* bits.
uint32_t claims_of(const tacta_descriptor& model);

}  // namespace tacta::conformance
