// An out-of-tree model plugin: bodies move under their external forces alone (no elasticity,
// symplectic Euler), with the installed model helpers doing the checks an in-tree model does
// (tacta::models::check_free_node_masses at create, DivergenceGuard in step). It exists to prove
// that tacta::models_common is installed and links outside the source tree.
#include <array>
#include <span>

#include "tacta/models/divergence_guard.hpp"
#include "tacta/models/tet_geometry.hpp"
#include "tacta/sdk/model.hpp"

namespace {

class ExternalFreeBody {
 public:
  static constexpr const char* kName = "external_free_body";
  static constexpr const char* kDescription = "out-of-tree model using the installed model helpers";
  static constexpr uint32_t kVersion = 100;
  static constexpr std::array<tacta_param_spec, 1> kParams{
      tacta::sdk::real_param("stretch_limit", "", 10.0, 1.5, 1000.0,
                             "edge length ratio beyond which the body is reported diverged"),
  };
  explicit ExternalFreeBody(const tacta_model_setup& setup)
      : masses_(setup.masses), fixed_(setup.fixed) {
    const tacta::sdk::Params params(kParams, setup.params, setup.param_count);
    const uint32_t n = setup.mesh->node_count;
    tacta::models::check_free_node_masses(kName, {setup.masses, n},
                                          {setup.fixed, setup.fixed ? n : 0u});
    guard_ = tacta::models::DivergenceGuard(*setup.mesh, params.real("stretch_limit"));
  }
  uint32_t step(tacta_body_state& state, double dt) noexcept {
    for (uint32_t i = 0; i < state.node_count; ++i) {
      if (fixed_ != nullptr && fixed_[i] != 0) continue;
      for (int c = 0; c < 3; ++c) {
        state.velocities[3 * i + c] += dt * state.external_forces[3 * i + c] / masses_[i];
        state.positions[3 * i + c] += dt * state.velocities[3 * i + c];
      }
    }
    return guard_.check(state.positions, state.velocities);
  }

 private:
  const double* masses_;  // kg, 1 per node, owned by the engine
  const uint8_t* fixed_;  // 1 per node or null
  tacta::models::DivergenceGuard guard_;
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<ExternalFreeBody>())
