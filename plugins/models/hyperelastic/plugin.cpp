// hyperelastic plugin: descriptor, parameter schema and the SDK glue around HyperelasticModel.
#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>

#include "hyperelastic_model.hpp"
#include "solver_params.hpp"
#include "tacta/sdk/model.hpp"

namespace tacta::models::hyperelastic {
namespace {

using tacta::models::load_state_blob;
using tacta::models::save_state_blob;
using tacta::models::StateHeader;

// Nodal averaging costs a wider matrix (a node couples with its 1-ring's 1-ring); below
// nu 0.45 per-element volumes lock little (VALIDATION.md), so auto keeps them there.
constexpr double kNodalAverageFromPoisson = 0.45;
Volumetric volumetric_choice(int choice, MaterialLaw law, double poisson_ratio) {
  if (choice == 1) return Volumetric::kElement;
  if (choice == 2) return Volumetric::kNodalAverage;
  return has_volumetric_term(law) && poisson_ratio >= kNodalAverageFromPoisson
             ? Volumetric::kNodalAverage
             : Volumetric::kElement;
}

class HyperelasticPlugin {
 public:
  static constexpr const char* kName = "hyperelastic";
  static constexpr const char* kDescription =
      "Hyperelastic tetrahedral FEM (Neo-Hookean, St Venant-Kirchhoff, Mooney-Rivlin), "
      "projected tangents, implicit Newton steps with line search, or static equilibrium";
  static constexpr uint32_t kVersion = 10000;
  // Forces depend on the deformation alone and sum to zero over each element. Rest data and
  // solver structure come from create(), so a rebuild on a cut mesh then begin() is exact.
  static constexpr uint32_t kClaims = TACTA_MODEL_CLAIM_ROTATION_INVARIANT |
                                      TACTA_MODEL_CLAIM_MOMENTUM | TACTA_MODEL_CLAIM_TOPOLOGY_EDITS;
  // Material and dynamic-step parameters; the static and linear solves come from sparse_solvers.
  static constexpr std::array<tacta_param_spec, 11> kModelParams = {
      sdk::choice_param("material", "neo_hookean|stvk|mooney_rivlin", 0,
                        "energy: compressible Neo-Hookean, St Venant-Kirchhoff, or compressible "
                        "Mooney-Rivlin (C10, C01, bulk modulus)"),
      sdk::real_param("c10", "Pa", 0.0, 0.0, 1e12,
                      "mooney_rivlin: C10; 0 with c01 0: C10 = mu/2 from the body's material"),
      sdk::real_param("c01", "Pa", 0.0, 0.0, 1e12, "mooney_rivlin: C01"),
      sdk::real_param("bulk_modulus", "Pa", 0.0, 0.0, 1e15,
                      "mooney_rivlin: K; 0: lambda + 2 mu / 3 from the body's material"),
      sdk::real_param("min_stretch", "", 0.1, 0.01, 0.9,
                      "principal stretches below this (and inverted ones) use the energy's "
                      "Taylor continuation"),
      sdk::choice_param("volumetric", "auto|element|nodal_average", 0,
                        "volumetric energy per element (locks as nu nears 0.5) or on nodally "
                        "averaged volumes (no locking; wider matrix); auto: nodal_average when "
                        "nu >= 0.45 and the law is neo_hookean or mooney_rivlin"),
      sdk::choice_param("tangent", "projected|exact", 0,
                        "projected: negative tangent eigenvalues set to 0 (robust); exact"),
      sdk::int_param("newton_iterations", 3, 1, 100,
                     "dynamic: Newton iterations per step, at most"),
      sdk::real_param("newton_tolerance", "", 1e-3, 1e-14, 1.0,
                      "dynamic: Newton stops when the residual falls below this fraction of "
                      "its first value"),
      sdk::int_param("tangent_reuse_steps", 4, 0, 1000,
                     "dynamic: steps whose first Newton correction reuses the last assembled "
                     "system (tangent, preconditioner, and the Rayleigh Kd, which is then up to "
                     "this many steps old) before a fresh one; the residual test is unchanged, "
                     "and a step needing a second correction assembles afresh; 0: every step"),
      sdk::real_param("tangent_reuse_change", "", 0.01, 0.0, 1.0,
                      "dynamic: ... and only while no element's deformation gradient F has moved "
                      "further than this (Frobenius norm) from the F of that assembly"),
  };
  static constexpr auto kParams = sparse::join_params(
      kModelParams,
      sparse::static_param_specs("dynamic: backward Euler steps; static: each "
                                 "step finds equilibrium under the current "
                                 "loads and held nodes (velocities 0)"),
      // CG to 1e-4: a tenth of newton_tolerance (inexact Newton), which the residual test
      // after each correction backs; tighter solves moved the liver demo by under 1e-6.
      sparse::solver_param_specs({.max_iterations = 50, .tolerance = 1e-4}));

  explicit HyperelasticPlugin(const tacta_model_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    const tacta_material& material = *setup.material;
    Options options;
    MaterialConstants& m = options.material;
    m.law = static_cast<MaterialLaw>(params.choice("material"));
    m.mu = material.lame_mu;
    m.lambda = material.lame_lambda;
    m.c10 = params.real("c10");
    m.c01 = params.real("c01");
    if (m.c10 == 0.0 && m.c01 == 0.0) m.c10 = 0.5 * m.mu;
    m.bulk = params.real("bulk_modulus");
    if (m.bulk == 0.0) m.bulk = m.lambda + 2.0 * m.mu / 3.0;
    m.min_stretch = params.real("min_stretch");
    if (m.law != MaterialLaw::kMooneyRivlin && !(m.mu > 0.0 && m.lambda + 2.0 * m.mu / 3.0 > 0.0))
      throw std::invalid_argument(
          "hyperelastic: the material needs lame_mu > 0 and a positive "
          "bulk modulus (got lambda " +
          std::to_string(m.lambda) + " Pa, mu " + std::to_string(m.mu) + " Pa)");
    if (m.law == MaterialLaw::kMooneyRivlin && !(m.c10 + m.c01 > 0.0 && m.bulk > 0.0))
      throw std::invalid_argument(
          "hyperelastic: mooney_rivlin needs c10 + c01 > 0 and a "
          "positive bulk modulus");
    options.volumetric =
        volumetric_choice(params.choice("volumetric"), m.law, material.poisson_ratio);
    options.project_tangent = params.choice("tangent") == 0;
    options.newton_iterations = params.integer("newton_iterations");
    options.newton_tolerance = params.real("newton_tolerance");
    options.tangent_reuse_steps = params.integer("tangent_reuse_steps");
    options.tangent_reuse_change = params.real("tangent_reuse_change");
    options.mode =
        sparse::read_static_params(params, options) ? SolveMode::kStatic : SolveMode::kDynamic;
    sparse::read_solver_params(params, options.solver);
    // An engine older than the host services passes a shorter setup: no workers then.
    if (setup.struct_size >= offsetof(tacta_model_setup, host) + sizeof setup.host)
      options.host = setup.host;
    const uint32_t n = setup.mesh->node_count;
    model_ = std::make_unique<HyperelasticModel>(
        *setup.mesh, material, std::span<const double>(setup.masses, n),
        setup.fixed ? std::span<const uint8_t>(setup.fixed, n) : std::span<const uint8_t>(),
        options);
  }
  uint32_t step(tacta_body_state& state, double dt) noexcept { return model_->step(state, dt); }
  void begin(const tacta_body_state& state, double dt) noexcept { model_->begin(state, dt); }
  double elastic_energy(const double* x) noexcept { return model_->elastic_energy(x); }
  void internal_forces(const double* x, double* f) noexcept { model_->internal_forces(x, f); }
  void node_stress(const double* x, double* s) noexcept { model_->node_stress(x, s); }
  size_t save_state(void* bytes, size_t capacity) noexcept {
    return save_state_blob(state_header(), bytes, capacity,
                           [&](StateIo& io) { model_->state_fields(io); });
  }
  void load_state(const void* bytes, size_t size) {
    load_state_blob(state_header(), bytes, size, [&](StateIo& io) { model_->state_fields(io); });
  }
  uint32_t counters(tacta_model_counter* out, uint32_t capacity) noexcept {
    const NewtonCounters& c = model_->counters();
    return sparse::report_counters(
        std::array<tacta_model_counter, 10>{{
            {"steps", static_cast<double>(c.steps)},
            {"newton_iterations", static_cast<double>(c.newton_iterations)},
            {"line_search_backtracks", static_cast<double>(c.line_search_backtracks)},
            {"unconverged_steps", static_cast<double>(c.unconverged_steps)},
            {"static_solves", static_cast<double>(c.static_solves)},
            {"load_increments", static_cast<double>(c.load_increments)},
            {"load_cuts", static_cast<double>(c.load_cuts)},
            {"inverted_element_steps", static_cast<double>(c.inverted_element_steps)},
            {"last_static_residual_N", c.last_static_residual},
            {"lagged_tangents", static_cast<double>(c.lagged_tangents)},
        }},
        model_->solver_counters(), out, capacity);
  }

 private:
  static constexpr uint32_t kStateVersion = 1;  // HyperelasticModel::state_fields' layout
  StateHeader state_header() const {
    return {kName, kStateVersion, model_->node_count(), model_->element_count()};
  }
  std::unique_ptr<HyperelasticModel> model_;
};

}  // namespace
}  // namespace tacta::models::hyperelastic

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<tacta::models::hyperelastic::HyperelasticPlugin>())
