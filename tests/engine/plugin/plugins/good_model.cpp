// Test plugin: a well-formed model written with the SDK. Each node is tied to its rest position
// by a spring of stiffness k (N/m) and integrated with semi-implicit Euler, so one step has a
// closed form the tests check: v1 = v0 + dt (f - k u) / m, x1 = x0 + dt v1.
#include <array>
#include <vector>

#include "tacta/sdk/model.hpp"

namespace {

class AnchorSprings {
 public:
  static constexpr const char* kName = "test_anchor_springs";
  static constexpr const char* kDescription = "nodes tied to their rest positions (test only)";
  static constexpr uint32_t kVersion = 10203;  // 1.2.3
  static constexpr std::array<tacta_param_spec, 4> kParams{
      tacta::sdk::real_param("stiffness", "N/m", 100.0, 0.0, 1e9, "anchor spring stiffness"),
      tacta::sdk::choice_param("integrator", "semi_implicit|explicit", 0, "time integrator"),
      tacta::sdk::vector_param("offset", "m", 3, "0 0 0", -1.0, 1.0,
                               "rest offset added to every node"),
      tacta::sdk::int_param("substeps", 1, 1, 100, "substeps per step"),
  };

  explicit AnchorSprings(const tacta_model_setup& setup)
      : rest_(setup.mesh->rest_positions, setup.mesh->rest_positions + 3 * setup.mesh->node_count),
        masses_(setup.masses, setup.masses + setup.mesh->node_count) {
    const tacta::sdk::Params params(kParams, setup.params, setup.param_count);
    stiffness_ = params.real("stiffness");
    substeps_ = params.integer("substeps");
    const auto offset = params.vector("offset");
    for (size_t i = 0; i < rest_.size() && offset.size() == 3; ++i) rest_[i] += offset[i % 3];
  }

  uint32_t step(tacta_body_state& state, double dt) noexcept {
    const double h = dt / substeps_;
    for (int s = 0; s < substeps_; ++s)
      for (uint32_t i = 0; i < 3 * state.node_count; ++i) {
        const double force =
            state.external_forces[i] - stiffness_ * (state.positions[i] - rest_[i]);
        state.velocities[i] += h * force / masses_[i / 3];
        state.positions[i] += h * state.velocities[i];
      }
    return TACTA_STEP_OK;
  }

  // Spring energy sum k |u|^2 / 2, J.
  double elastic_energy(const double* positions) noexcept {
    double energy = 0;
    for (size_t i = 0; i < rest_.size(); ++i)
      energy += 0.5 * stiffness_ * (positions[i] - rest_[i]) * (positions[i] - rest_[i]);
    return energy;
  }

 private:
  std::vector<double> rest_;    // m
  std::vector<double> masses_;  // kg
  double stiffness_ = 0;        // N/m
  int substeps_ = 1;
};

}  // namespace

// Registering the same descriptor twice must be harmless.
TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<AnchorSprings>(),
                    tacta::sdk::model_descriptor<AnchorSprings>())
