// corotational_fem plugin: descriptor, parameter schema and the SDK glue around CorotationalFem.
#include <array>
#include <cmath>
#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "corotational_fem.hpp"
#include "solver_params.hpp"
#include "tacta/sdk/model.hpp"

namespace tacta::models::corotational {
namespace {

using tacta::models::load_state_blob;
using tacta::models::save_state_blob;
using tacta::models::StateHeader;

class CorotationalFemPlugin {
 public:
  static constexpr const char* kName = "corotational_fem";
  static constexpr const char* kDescription =
      "Corotational linear tetrahedral FEM, implicit Euler with Rayleigh damping (PCG or "
      "sparse Cholesky)";
  static constexpr uint32_t kVersion = 10000;
  // Forces depend on the deformation alone and sum to zero over each element. Rotations are
  // taken from the positions each step and factorisations come from create(), so a rebuild on a
  // cut mesh then begin() is exact.
  static constexpr uint32_t kClaims = TACTA_MODEL_CLAIM_ROTATION_INVARIANT |
                                      TACTA_MODEL_CLAIM_MOMENTUM | TACTA_MODEL_CLAIM_TOPOLOGY_EDITS;
  // The solver's limits; rotation, solver and preconditioner size the buffers built at creation.
  static constexpr const char* kLiveParams = "max_iterations|tolerance|refactor_interval";
  static constexpr auto kParams = sparse::join_params(
      std::array{sdk::choice_param("rotation", "polar|svd", 0,
                                   "element rotation: polar (warm-started iteration) or svd "
                                   "(inversion-aware)")},
      sparse::solver_param_specs({.max_iterations = 25, .tolerance = 1e-5}),
      sparse::static_param_specs("dynamic: implicit Euler steps; static: each step finds "
                                 "equilibrium under the current loads and held nodes (velocities "
                                 "0)"),
      std::array{sdk::choice_param("guess", "adaptive|linear", 0,
                                   "CG's starting dv: extrapolated linearly over two steps, or "
                                   "(adaptive) quadratically over three after a step where that "
                                   "missed by less"),
                 sdk::choice_param("tolerance_scale", "forces|rhs", 0,
                                   "what tolerance is a fraction of: the larger of the rhs norm "
                                   "and the step's force impulse h (|f_int|^2 + |f_ext|^2)^1/2 "
                                   "(forces), or the rhs norm alone, which near equilibrium is "
                                   "what is left of forces that cancel (rhs)"),
                 sdk::bool_param("threaded_solve", true,
                                 "with scene threads >= 2 and 384+ nodes: the row passes and the "
                                 "(block) Jacobi CG on the engine's workers too, not only the "
                                 "element pass, in the steps the body has the workers to itself "
                                 "(stepped in a group of bodies, one per thread, it runs the "
                                 "serial solve)")});

  explicit CorotationalFemPlugin(const tacta_model_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    Options options;
    // An engine older than the host services passes a shorter setup: no workers then.
    if (setup.struct_size >= offsetof(tacta_model_setup, host) + sizeof setup.host)
      options.host = setup.host;
    options.rotation = static_cast<RotationMethod>(params.choice("rotation"));
    sparse::read_solver_params(params, options);
    options.static_solve = sparse::read_static_params(params, options);
    options.threaded_solve = params.flag("threaded_solve");
    options.adaptive_guess = params.choice("guess") == 0;
    options.force_scaled_tolerance = params.choice("tolerance_scale") == 0;
    const uint32_t n = setup.mesh->node_count;
    model_ = std::make_unique<CorotationalFem>(
        *setup.mesh, *setup.material, std::span<const double>(setup.masses, n),
        setup.fixed ? std::span<const uint8_t>(setup.fixed, n) : std::span<const uint8_t>(),
        options);
  }
  uint32_t step(tacta_body_state& state, double dt) noexcept { return model_->step(state, dt); }
  void begin(const tacta_body_state& state, double dt) noexcept { model_->begin(state, dt); }
  double elastic_energy(const double* x) noexcept { return model_->elastic_energy(x); }
  void internal_forces(const double* x, double* f) noexcept { model_->internal_forces(x, f); }
  void node_stress(const double* x, double* s) noexcept { model_->node_stress(x, s); }
  uint32_t counters(tacta_model_counter* out, uint32_t capacity) noexcept {
    const StaticCounters& s = model_->static_counters();
    return sparse::report_counters(
        std::array<tacta_model_counter, 6>{{
            {"static_solves", static_cast<double>(s.solves)},
            {"static_newton_iterations", static_cast<double>(s.newton_iterations)},
            {"load_increments", static_cast<double>(s.load_increments)},
            {"load_cuts", static_cast<double>(s.load_cuts)},
            {"unconverged_static_solves", static_cast<double>(s.unconverged)},
            {"last_static_residual_N", s.last_residual},
        }},
        model_->counters(), out, capacity);
  }
  size_t save_state(void* bytes, size_t capacity) noexcept {
    return save_state_blob(state_header(), bytes, capacity,
                           [&](StateIo& io) { model_->state_fields(io); });
  }
  void load_state(const void* bytes, size_t size) {
    load_state_blob(state_header(), bytes, size, [&](StateIo& io) { model_->state_fields(io); });
  }
  // Live changes reach the solver's limits only (max_iterations, tolerance, refactor_interval):
  // rotation, solver and preconditioner decide the buffers built at creation.
  void set_param(uint32_t index, const tacta_param_value& value) {
    if (index >= kParams.size())
      throw std::invalid_argument("corotational_fem: no parameter with index " +
                                  std::to_string(index));
    const tacta_param_spec& spec = kParams[index];
    const std::string_view name = spec.name;
    if (name != "max_iterations" && name != "tolerance" && name != "refactor_interval")
      throw std::invalid_argument("corotational_fem: '" + std::string(name) +
                                  "' cannot change while running (only max_iterations, "
                                  "tolerance and refactor_interval can)");
    const double v = value.number;
    if (!(v >= spec.min_value && v <= spec.max_value) ||
        (spec.type == TACTA_PARAM_INT && v != std::floor(v)))
      throw std::invalid_argument(
          "corotational_fem: " + std::string(name) + " = " + std::to_string(v) + " is outside [" +
          std::to_string(spec.min_value) + ", " + std::to_string(spec.max_value) + "]" +
          (spec.type == TACTA_PARAM_INT ? " or not an integer" : ""));
    Options options = model_->options();
    if (name == "max_iterations") options.max_iterations = static_cast<int>(v);
    if (name == "tolerance") options.tolerance = v;
    if (name == "refactor_interval") options.refactor_interval = static_cast<int>(v);
    model_->set_solver_limits(options.max_iterations, options.tolerance, options.refactor_interval);
  }

 private:
  StateHeader state_header() const {
    return {kName, kStateVersion, model_->node_count(), model_->element_count()};
  }
  static constexpr uint32_t kStateVersion = 2;  // CorotationalFem::state_fields' layout
  std::unique_ptr<CorotationalFem> model_;
};

}  // namespace
}  // namespace tacta::models::corotational

TACTA_PLUGIN_EXPORT(
    tacta::sdk::model_descriptor<tacta::models::corotational::CorotationalFemPlugin>())
