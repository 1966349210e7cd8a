// Test plugin: a stable model that faults on purpose. Every node is tied to its rest position by
// a damped spring (semi-implicit Euler), so the body reacts to contact and gravity but stays
// bounded; at step `fault_step` (0-based count of step() calls) it either writes NaN into the
// first free node's position (fault_kind: nan) or returns TACTA_STEP_DIVERGED (fault_kind:
// diverged), or never faults (fault_kind: none), or from that step on returns the warning
// TACTA_STEP_SOLVER_NOT_CONVERGED (fault_kind: warn). It also counts its live instances, exported as
// tacta_test_fault_model_live_instances(), so tests can check that a failed load destroyed every
// instance it built.
#include <array>
#include <atomic>
#include <limits>
#include <vector>

#include "tacta/sdk/model.hpp"

namespace {

std::atomic<int> live_instances{0};

class FaultModel {
 public:
  static constexpr const char* kName = "test_fault_model";
  static constexpr const char* kDescription =
      "damped anchor springs that fault at a chosen step (test only)";
  static constexpr uint32_t kVersion = 10000;
  static constexpr std::array<tacta_param_spec, 4> kParams{
      tacta::sdk::real_param("stiffness", "N/m", 2000.0, 0.0, 1e9,
                             "anchor spring stiffness per node"),
      tacta::sdk::real_param("damping", "N s/m", 5.0, 0.0, 1e9, "damper per node"),
      tacta::sdk::int_param("fault_step", 100, 0, 100000000, "step() call that faults"),
      tacta::sdk::choice_param("fault_kind", "nan|diverged|none|warn", 0,
                               "what the faulting step does"),
  };

  explicit FaultModel(const tacta_model_setup& setup)
      : rest_(setup.mesh->rest_positions, setup.mesh->rest_positions + 3 * setup.mesh->node_count),
        masses_(setup.masses, setup.masses + setup.mesh->node_count),
        fixed_(setup.fixed, setup.fixed + setup.mesh->node_count) {
    const tacta::sdk::Params params(kParams, setup.params, setup.param_count);
    stiffness_ = params.real("stiffness");
    damping_ = params.real("damping");
    fault_step_ = params.integer("fault_step");
    fault_kind_ = params.choice("fault_kind");
    ++live_instances;
  }
  ~FaultModel() { --live_instances; }
  FaultModel(const FaultModel&) = delete;
  FaultModel& operator=(const FaultModel&) = delete;

  uint32_t step(tacta_body_state& state, double dt) noexcept {
    const int64_t call = steps_++;
    for (uint32_t i = 0; i < 3 * state.node_count; ++i) {
      if (fixed_[i / 3]) continue;
      const double force = state.external_forces[i] - stiffness_ * (state.positions[i] - rest_[i]) -
                           damping_ * state.velocities[i];
      state.velocities[i] += dt * force / masses_[i / 3];
      state.positions[i] += dt * state.velocities[i];
    }
    if (fault_kind_ == 3)
      return call >= fault_step_ ? TACTA_STEP_SOLVER_NOT_CONVERGED : TACTA_STEP_OK;
    if (call != fault_step_) return TACTA_STEP_OK;
    if (fault_kind_ == 1) return TACTA_STEP_DIVERGED;
    if (fault_kind_ == 0) {
      for (uint32_t n = 0; n < state.node_count; ++n)
        if (!fixed_[n]) {
          state.positions[3 * n + 1] = std::numeric_limits<double>::quiet_NaN();
          break;
        }
    }
    return TACTA_STEP_OK;
  }

 private:
  std::vector<double> rest_;    // m
  std::vector<double> masses_;  // kg
  std::vector<uint8_t> fixed_;
  double stiffness_ = 0;  // N/m
  double damping_ = 0;    // N s/m
  int64_t fault_step_ = 0;
  int fault_kind_ = 0;
  int64_t steps_ = 0;
};

}  // namespace

extern "C" __attribute__((visibility("default"))) int tacta_test_fault_model_live_instances() {
  return live_instances.load();
}

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<FaultModel>())
