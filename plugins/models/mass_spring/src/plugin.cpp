// mass_spring plugin: descriptor, parameter schema and the SDK adapter around MassSpringModel.
#include <algorithm>
#include <array>
#include <string>

#include "mass_spring_model.hpp"
#include "tacta/sdk/model.hpp"

namespace {

using tacta::models::MassSpringModel;
using tacta::models::MassSpringOptions;

class MassSpringPlugin {
 public:
  static constexpr const char* kName = "mass_spring";
  static constexpr const char* kDescription =
      "Mass-spring on the mesh edges (spring constants from E, nu): symplectic Euler, "
      "Baraff-Witkin "
      "implicit Euler, Desbrun's precomputed linear part";
  static constexpr uint32_t kVersion = 10000;
  // Forces depend on the deformation alone and sum to zero over each element. No history: every
  // integrator starts each step from x and v alone (Baraff-Witkin's CG from dv = 0, Desbrun's
  // factor fixed at creation), so a rebuild on a cut mesh continues exactly.
  static constexpr uint32_t kClaims = TACTA_MODEL_CLAIM_ROTATION_INVARIANT |
                                      TACTA_MODEL_CLAIM_MOMENTUM | TACTA_MODEL_CLAIM_NO_HISTORY |
                                      TACTA_MODEL_CLAIM_TOPOLOGY_EDITS;
  static constexpr std::array<tacta_param_spec, 7> kParams = {
      tacta::sdk::choice_param("integrator", "symplectic_euler|implicit_euler|desbrun", 1,
                               "time integrator; implicit_euler is Baraff-Witkin (one Newton "
                               "step, CG); desbrun factorises its matrix for the setup dt"),
      tacta::sdk::real_param("damping", "N s/m", 0.0, 0.0, 1e6,
                             "viscous damping per node, added to the material's alpha * m"),
      tacta::sdk::int_param("cg_max_iterations", 200, 1, 10000,
                            "Baraff-Witkin: conjugate-gradient iteration limit per step"),
      tacta::sdk::real_param("cg_tolerance", "", 1e-8, 1e-14, 1e-1,
                             "Baraff-Witkin: relative residual at which CG stops"),
      tacta::sdk::bool_param("desbrun_correction", true,
                             "desbrun: remove the spurious angular momentum of the linear filter "
                             "(only when no node is fixed)"),
      tacta::sdk::real_param("divergence_stretch", "", 10.0, 1.5, 1e6,
                             "fault when an edge grows past this multiple of its rest length"),
      tacta::sdk::choice_param(
          "stiffness_rule", "van_gelder|fem_projection", 0,
          "spring constants from E and nu: Van Gelder's E V / L^2 (nu ignored), "
          "or each tet's linear-FEM edge block projected on the spring"),
  };

  explicit MassSpringPlugin(const tacta_model_setup& setup) : model_(setup, options(setup)) {}

  uint32_t step(tacta_body_state& state, double dt) noexcept { return model_.step(state, dt); }
  double elastic_energy(const double* x) noexcept { return model_.elastic_energy(x); }
  void internal_forces(const double* x, double* f) noexcept { model_.internal_forces(x, f); }
  std::string describe() const {
    const auto& k = model_.springs().stiffness;
    const auto slack = std::count(k.begin(), k.end(), 0.0);
    return std::string("spring constants by ") +
           tacta::models::stiffness_rule_name(model_.options().stiffness_rule) + ": " +
           tacta::models::median_and_range(k) + " N/m over " + std::to_string(k.size()) + " edges" +
           (slack ? ", " + std::to_string(slack) + " of them 0 (obtuse tets)" : "");
  }

 private:
  static MassSpringOptions options(const tacta_model_setup& setup) {
    const tacta::sdk::Params p(kParams, setup.params, setup.param_count);
    MassSpringOptions o;
    o.integrator = static_cast<MassSpringOptions::Integrator>(p.choice("integrator"));
    o.damping = p.real("damping");
    o.cg_max_iterations = p.integer("cg_max_iterations");
    o.cg_tolerance = p.real("cg_tolerance");
    o.desbrun_correction = p.flag("desbrun_correction");
    o.divergence_stretch = p.real("divergence_stretch");
    o.stiffness_rule = static_cast<tacta::models::StiffnessRule>(p.choice("stiffness_rule"));
    return o;
  }
  MassSpringModel model_;
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<MassSpringPlugin>())
