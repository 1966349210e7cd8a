// fd_debunne plugin: descriptor, parameter schema and the SDK adapter around FdDebunneModel.
#include <array>

#include "fd_debunne_model.hpp"
#include "tacta/sdk/model.hpp"

namespace {

using tacta::models::FdDebunneModel;
using tacta::models::FdDebunneOptions;

class FdDebunnePlugin {
 public:
  static constexpr const char* kName = "fd_debunne";
  static constexpr const char* kDescription =
      "Debunne et al.: finite differences of the Navier equation on the mesh edge graph, explicit";
  static constexpr uint32_t kVersion = 10000;
  // Finite differences on the edge graph: neither rotation-invariant nor momentum-conserving.
  // No history: both explicit integrators step from x and v alone.
  static constexpr uint32_t kClaims = TACTA_MODEL_CLAIM_NO_HISTORY;
  static constexpr const char* kLiveParams = "damping";
  static constexpr std::array<tacta_param_spec, 5> kParams = {
      tacta::sdk::choice_param("integrator", "symplectic_euler|explicit_euler", 0,
                               "time integrator; explicit_euler is the paper's forward Euler"),
      tacta::sdk::real_param("damping", "N s/m", 0.0, 0.0, 1e6,
                             "viscous damping: force -damping * v on every node"),
      tacta::sdk::bool_param("symmetric", false,
                             "equal and opposite pair forces (conserves linear momentum); "
                             "false = the paper's per-node normalisation"),
      tacta::sdk::choice_param("operator_scale", "paper|dimension", 1,
                               "factor on eqs. 13 and 17: 1 as printed, or the mesh dimension "
                               "(right wave speeds on Cartesian edge graphs)"),
      tacta::sdk::real_param("divergence_stretch", "", 10.0, 1.5, 1e6,
                             "fault when an edge grows past this multiple of its rest length"),
  };

  explicit FdDebunnePlugin(const tacta_model_setup& setup) : model_(setup, options(setup)) {}

  uint32_t step(tacta_body_state& state, double dt) noexcept { return model_.step(state, dt); }
  double elastic_energy(const double* x) noexcept { return model_.elastic_energy(x); }
  void internal_forces(const double* x, double* f) noexcept { model_.internal_forces(x, f); }
  void set_param(uint32_t index, const tacta_param_value& value) {
    if (index != 1)
      throw std::invalid_argument("fd_debunne: only 'damping' can change while running");
    model_.set_damping(value.number);
  }

 private:
  static FdDebunneOptions options(const tacta_model_setup& setup) {
    const tacta::sdk::Params p(kParams, setup.params, setup.param_count);
    FdDebunneOptions o;
    o.integrator = static_cast<FdDebunneOptions::Integrator>(p.choice("integrator"));
    o.damping = p.real("damping");
    o.symmetric = p.flag("symmetric");
    o.operator_scale = static_cast<FdDebunneOptions::OperatorScale>(p.choice("operator_scale"));
    o.divergence_stretch = p.real("divergence_stretch");
    return o;
  }
  FdDebunneModel model_;
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<FdDebunnePlugin>())
