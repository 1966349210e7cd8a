// Scene parameters the implicit models share (corotational_fem, hyperelastic): the linear solve
// (sparse::SolverOptions) and the static solve, as schema entries with per-model defaults, read
// back into a model's options, and the model counters report with the solver's counters appended.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

#include "safe_solver.hpp"
#include "tacta/model_api.h"
#include "tacta/sdk/model.hpp"

namespace tacta::models::sparse {

// The defaults that differ between models.
struct SolverParamDefaults {
  int max_iterations;  // CG iterations per solve
  double tolerance;    // CG relative residual
};

// solver, preconditioner, max_iterations, tolerance, refactor_interval, fallback, restart_factor.
constexpr std::array<tacta_param_spec, 7> solver_param_specs(SolverParamDefaults d) {
  return {
      sdk::choice_param("solver", "pcg|cholesky", 0,
                        "linear solver: warm-started preconditioned CG with fallbacks, or sparse "
                        "LDL^T"),
      sdk::choice_param("preconditioner", "jacobi|block_jacobi|incomplete_cholesky", 1,
                        "CG preconditioner: diagonal, inverse 3x3 diagonal blocks, or block "
                        "incomplete Cholesky IC(0)"),
      sdk::int_param("max_iterations", d.max_iterations, 1, 10000,
                     "CG iterations per solve before the fallbacks"),
      sdk::real_param("tolerance", "", d.tolerance, 1e-14, 1.0,
                      "CG stops when the residual norm falls below this fraction of the rhs norm"),
      sdk::int_param("refactor_interval", 1, 1, 1000,
                     "incomplete_cholesky: solves between refactorisations (1: every solve)"),
      sdk::choice_param(
          "fallback", "direct|restart|none", 0,
          "when CG has not converged: restart from its last iterate with restart_factor x "
          "max_iterations, then sparse LDL^T (direct); the restart only; or "
          "accept the unconverged solution (none)"),
      sdk::int_param("restart_factor", 8, 1, 1000,
                     "the restart's iteration cap, in units of max_iterations"),
  };
}

// solve, load_steps, static_iterations, static_tolerance; solve_help says what a dynamic step is.
constexpr std::array<tacta_param_spec, 4> static_param_specs(const char* solve_help) {
  return {
      sdk::choice_param("solve", "dynamic|static", 0, solve_help),
      sdk::int_param("load_steps", 1, 1, 10000, "static: increments per solve (halved on failure)"),
      sdk::int_param("static_iterations", 25, 1, 1000, "static: Newton iterations per increment"),
      sdk::real_param("static_tolerance", "", 1e-6, 1e-14, 1.0,
                      "static: converged when |f_int + f_ext| on free nodes is below this "
                      "fraction of the load (or reaction) norm"),
  };
}

// One schema out of groups, in the order given.
template <size_t... N>
constexpr std::array<tacta_param_spec, (N + ...)> join_params(
    const std::array<tacta_param_spec, N>&... groups) {
  std::array<tacta_param_spec, (N + ...)> all{};
  size_t at = 0;
  ((std::copy(groups.begin(), groups.end(), all.begin() + static_cast<std::ptrdiff_t>(at)),
    at += N),
   ...);
  return all;
}

// The solver_param_specs() values into any options struct with SolverOptions' member names.
template <class Options>
void read_solver_params(const sdk::Params& params, Options& options) {
  options.solver = static_cast<LinearSolver>(params.choice("solver"));
  options.preconditioner = static_cast<Preconditioner>(params.choice("preconditioner"));
  options.max_iterations = params.integer("max_iterations");
  options.tolerance = params.real("tolerance");
  options.refactor_interval = params.integer("refactor_interval");
  options.fallback = static_cast<SolverFallback>(params.choice("fallback"));
  options.restart_factor = params.integer("restart_factor");
}

// The static_param_specs() values (load_steps, static_iterations, static_tolerance) into the
// model's options; returns whether `solve` is static.
template <class Options>
bool read_static_params(const sdk::Params& params, Options& options) {
  options.load_steps = params.integer("load_steps");
  options.static_iterations = params.integer("static_iterations");
  options.static_tolerance = params.real("static_tolerance");
  return params.choice("solve") == 1;
}

// The model's own counters followed by the linear solver's (named_counters), copied into out.
template <size_t N>
uint32_t report_counters(const std::array<tacta_model_counter, N>& own,
                         const SolverCounters& solver, tacta_model_counter* out,
                         uint32_t capacity) noexcept {
  const auto named = named_counters(solver);
  std::array<tacta_model_counter, N + std::tuple_size_v<decltype(named)>> all{};
  std::copy(own.begin(), own.end(), all.begin());
  std::copy(named.begin(), named.end(), all.begin() + static_cast<std::ptrdiff_t>(N));
  return sdk::copy_counters(all.data(), static_cast<uint32_t>(all.size()), out, capacity);
}

}  // namespace tacta::models::sparse
