// tensor_mass plugin: descriptor, parameter schema and the SDK adapter around TensorMassModel.
#include <array>
#include <string>

#include "tacta/sdk/model.hpp"
#include "tensor_mass_model.hpp"

namespace {

using tacta::models::TensorMassModel;
using tacta::models::TensorMassOptions;

class TensorMassPlugin {
 public:
  static constexpr const char* kName = "tensor_mass";
  static constexpr const char* kDescription =
      "Delingette et al.: linear tetrahedral FEM, K_ii per vertex and K_ij per edge";
  static constexpr uint32_t kVersion = 10000;
  // Linear (small strain): a rigid rotation strains it, but K u sums to zero over the nodes. The
  // only history (the previous position) is set again by begin(), so a cut mesh is a rebuild.
  static constexpr uint32_t kClaims = TACTA_MODEL_CLAIM_MOMENTUM | TACTA_MODEL_CLAIM_TOPOLOGY_EDITS;
  static constexpr std::array<tacta_param_spec, 3> kParams = {
      tacta::sdk::choice_param("integrator", "central_difference|implicit_euler|auto", 2,
                               "explicit central differences, implicit Euler factorised at create "
                               "for the setup dt, or auto: central differences where stable at dt"),
      tacta::sdk::real_param("damping", "N s/m", 0.0, 0.0, 1e6,
                             "viscous damping per node, added to the material's alpha * m"),
      tacta::sdk::real_param("divergence_stretch", "", 10.0, 1.5, 1e6,
                             "fault when an edge grows past this multiple of its rest length"),
  };

  explicit TensorMassPlugin(const tacta_model_setup& setup) : model_(setup, options(setup)) {}

  void begin(const tacta_body_state& state, double dt) noexcept { model_.begin(state, dt); }
  uint32_t step(tacta_body_state& state, double dt) noexcept { return model_.step(state, dt); }
  double elastic_energy(const double* x) noexcept { return model_.elastic_energy(x); }
  void internal_forces(const double* x, double* f) noexcept { model_.internal_forces(x, f); }
  std::string describe() const { return model_.note(); }
  size_t save_state(void* bytes, size_t capacity) noexcept {
    return tacta::models::save_state_blob(
        state_header(), bytes, capacity,
        [&](tacta::models::StateIo& io) { model_.state_fields(io); });
  }
  void load_state(const void* bytes, size_t size) {
    tacta::models::load_state_blob(state_header(), bytes, size,
                                   [&](tacta::models::StateIo& io) { model_.state_fields(io); });
  }

 private:
  static constexpr uint32_t kStateVersion = 1;  // TensorMassModel::state_fields' layout
  tacta::models::StateHeader state_header() const {
    return {kName, kStateVersion, model_.node_count(),
            static_cast<uint32_t>(model_.edges().size() / 2)};
  }
  static TensorMassOptions options(const tacta_model_setup& setup) {
    const tacta::sdk::Params p(kParams, setup.params, setup.param_count);
    TensorMassOptions o;
    o.integrator = static_cast<TensorMassOptions::Integrator>(p.choice("integrator"));
    o.damping = p.real("damping");
    o.divergence_stretch = p.real("divergence_stretch");
    return o;
  }
  TensorMassModel model_;
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<TensorMassPlugin>())
