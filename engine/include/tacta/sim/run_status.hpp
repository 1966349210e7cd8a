// Run-time status as a run reports it: the warning and error bits seen per body (model steps),
// per device and for the collision pipeline, each with the ticks it was seen on and a one-line
// remedy, and which collision plugin served which role. Filled after the run
// (engine/src/report/run_status_gather.cpp); report.json and `tacta run` print it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tacta {

enum class StatusSeverity { Info, Warning, Error };

struct StatusBitCount {
  std::string name;  // e.g. "solver_not_converged"
  uint32_t bit = 0;  // the bit's value in its source's bit set
  StatusSeverity severity = StatusSeverity::Warning;
  uint64_t ticks = 0;  // ticks (or steps) the bit was raised on
  double first_time_s = 0;
  std::string remedy;  // one line
};

struct CollisionPluginResult {
  std::string name;
  uint32_t roles = 0;          // TACTA_COLLISION_ROLE_* it declares
  bool roles_guessed = false;  // no `roles` in its table: guessed from its entries
  uint32_t serves = 0;         // the roles the engine gave it
};

struct RunStatus {
  std::vector<std::vector<StatusBitCount>> bodies;   // per body, model step bits
  std::vector<std::vector<StatusBitCount>> devices;  // per device
  std::vector<StatusBitCount> collision;             // the collision pipeline (not per body)
  std::vector<CollisionPluginResult> collision_plugins;
  uint32_t pairs_capacity = 0, contacts_capacity = 0;  // collision buffers, sized at load
  uint32_t pairs_high_water = 0, contacts_high_water = 0;
  // The proxy's hierarchies: slices refit, whole refits (a margin past its cap, or not sliced).
  uint64_t proxy_slices = 0, proxy_whole_refits = 0;
  // The proxy's patches: gathers (all; of them, those the upkeep made ahead of need) and the
  // queries they answered.
  uint64_t patch_gathers = 0, patch_upkeep_gathers = 0, patch_queries = 0;
  // Free-space checks answered clear without a search; of them, those the slices' boxes answered.
  uint64_t clear_answers = 0, clear_bound_answers = 0;
  bool proxy_sliced = false;  // the mode that ran: sliced, or every_tick (asked, or fallen back)
  size_t errors = 0, warnings = 0;  // kinds (who x bit) seen
  std::vector<std::string> lines;   // one per warning or error kind, for the console
};

// What ticks raised: the OR of each source's bits, and whether any of them is an error. One tick's
// (HapticLoop::last_status) or a whole Simulation::step call's (Simulation::step_status).
struct TickStatus {
  uint32_t model_bits = 0;      // TACTA_STEP_* over every body stepped
  uint32_t collision_bits = 0;  // TACTA_COLLIDE_*
  uint32_t device_bits = 0;  // device bits (engine/src/systems/status_bits.hpp) over every device
  bool error = false;
  void merge(const TickStatus& t) noexcept {
    model_bits |= t.model_bits;
    collision_bits |= t.collision_bits;
    device_bits |= t.device_bits;
    error = error || t.error;
  }
};

// What Simulation::step()/advance_to() did: the ticks that ran and what they raised.
struct StepResult {
  uint64_t ticks = 0;
  TickStatus status;
};

const char* severity_name(StatusSeverity s) noexcept;

}  // namespace tacta
