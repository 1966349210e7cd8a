// corotational_fem plugin: descriptor, parameter schema and the SDK glue around CorotationalFem.
#include <cstddef>
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

#include "corotational_fem.hpp"
#include "tacta/sdk/model.hpp"

namespace tacta::models::corotational {
namespace {

class CorotationalFemPlugin {
 public:
  static constexpr const char* kName = "corotational_fem";
  static constexpr const char* kDescription =
      "Corotational linear tetrahedral FEM, implicit Euler with Rayleigh damping (PCG or "
      "sparse Cholesky)";
  static constexpr uint32_t kVersion = 10000;
  // Forces depend on the deformation alone and sum to zero over each element.
  static constexpr uint32_t kClaims = TACTA_MODEL_CLAIM_ROTATION_INVARIANT | TACTA_MODEL_CLAIM_MOMENTUM;
  static constexpr std::array<tacta_param_spec, 12> kParams = {
      sdk::choice_param("rotation", "polar|svd", 0,
                        "element rotation: polar (warm-started iteration) or svd (inversion-aware)"),
      sdk::choice_param("solver", "pcg|cholesky", 0,
                        "linear solver: warm-started preconditioned CG, or sparse LDL^T"),
      sdk::choice_param("preconditioner", "jacobi|block_jacobi|incomplete_cholesky", 1,
                        "CG preconditioner: diagonal, inverse 3x3 diagonal blocks, or block "
                        "incomplete Cholesky IC(0)"),
      sdk::int_param("max_iterations", 25, 1, 10000, "CG iterations per step at most"),
      sdk::real_param("tolerance", "", 1e-5, 1e-14, 1.0,
                      "CG stops when the residual norm falls below this fraction of the rhs norm"),
      sdk::int_param("refactor_interval", 1, 1, 1000,
                     "incomplete_cholesky: steps between refactorisations (1: every step)"),
      sdk::choice_param("fallback", "direct|restart|none", 0,
                        "when CG has not converged: restart from zero with restart_factor x "
                        "max_iterations, then sparse LDL^T (direct); the restart only; or "
                        "accept the unconverged solution (none)"),
      sdk::int_param("restart_factor", 8, 1, 1000,
                     "the restart's iteration cap, in units of max_iterations"),
      sdk::choice_param("solve", "dynamic|static", 0,
                        "dynamic: implicit Euler steps; static: each step finds equilibrium "
                        "under the current loads and held nodes (velocities 0)"),
      sdk::int_param("load_steps", 1, 1, 10000, "static: increments per solve (halved on failure)"),
      sdk::int_param("static_iterations", 25, 1, 1000, "static: Newton iterations per increment"),
      sdk::real_param("static_tolerance", "", 1e-6, 1e-14, 1.0,
                      "static: converged when |f_int + f_ext| on free nodes is below this "
                      "fraction of the load (or reaction) norm"),
  };

  explicit CorotationalFemPlugin(const tacta_model_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    Options options;
    // An engine older than the host services passes a shorter setup: no workers then.
    if (setup.struct_size >= offsetof(tacta_model_setup, host) + sizeof setup.host) options.host = setup.host;
    options.rotation = static_cast<RotationMethod>(params.choice("rotation"));
    options.solver = static_cast<LinearSolver>(params.choice("solver"));
    options.preconditioner = static_cast<Preconditioner>(params.choice("preconditioner"));
    options.max_iterations = params.integer("max_iterations");
    options.tolerance = params.real("tolerance");
    options.refactor_interval = params.integer("refactor_interval");
    options.fallback = static_cast<SolverFallback>(params.choice("fallback"));
    options.restart_factor = params.integer("restart_factor");
    options.static_solve = params.choice("solve") == 1;
    options.load_steps = params.integer("load_steps");
    options.static_iterations = params.integer("static_iterations");
    options.static_tolerance = params.real("static_tolerance");
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
    const auto solver = sparse::named_counters(model_->counters());
    const StaticCounters& s = model_->static_counters();
    std::array<tacta_model_counter, 6 + solver.size()> all = {{
        {"static_solves", static_cast<double>(s.solves)},
        {"static_newton_iterations", static_cast<double>(s.newton_iterations)},
        {"load_increments", static_cast<double>(s.load_increments)},
        {"load_cuts", static_cast<double>(s.load_cuts)},
        {"unconverged_static_solves", static_cast<double>(s.unconverged)},
        {"last_static_residual_N", s.last_residual},
    }};
    std::copy(solver.begin(), solver.end(), all.begin() + 6);
    return sdk::copy_counters(all.data(), static_cast<uint32_t>(all.size()), out, capacity);
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
      throw std::invalid_argument("corotational_fem: " + std::string(name) + " = " +
                                  std::to_string(v) + " is outside [" +
                                  std::to_string(spec.min_value) + ", " +
                                  std::to_string(spec.max_value) + "]" +
                                  (spec.type == TACTA_PARAM_INT ? " or not an integer" : ""));
    Options options = model_->options();
    if (name == "max_iterations") options.max_iterations = static_cast<int>(v);
    if (name == "tolerance") options.tolerance = v;
    if (name == "refactor_interval") options.refactor_interval = static_cast<int>(v);
    model_->set_solver_limits(options.max_iterations, options.tolerance,
                              options.refactor_interval);
  }

 private:
  std::unique_ptr<CorotationalFem> model_;
};

}  // namespace
}  // namespace tacta::models::corotational

TACTA_PLUGIN_EXPORT(
    tacta::sdk::model_descriptor<tacta::models::corotational::CorotationalFemPlugin>())
