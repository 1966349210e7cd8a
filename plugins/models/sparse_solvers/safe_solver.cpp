#include "safe_solver.hpp"

#include <algorithm>
#include <cstddef>

#include "tacta/models/state_blob.hpp"

namespace tacta::models::sparse {

namespace {
constexpr int kMaxDirectHold = 64;  // solves on LDL^T before CG is tried again, at most
}

std::array<tacta_model_counter, 8> named_counters(const SolverCounters& c) {
  return {{{"solves", static_cast<double>(c.solves)},
           {"cg_iterations", static_cast<double>(c.cg_iterations)},
           {"warm_starts_rejected", static_cast<double>(c.warm_starts_rejected)},
           {"cg_restarts", static_cast<double>(c.restarts)},
           {"direct_fallbacks", static_cast<double>(c.direct_fallbacks)},
           {"direct_solves_held", static_cast<double>(c.direct_solves_held)},
           {"unconverged_solves", static_cast<double>(c.unconverged)},
           {"max_relative_residual", c.max_relative_residual}}};
}

SafeSolver::SafeSolver(const BlockSparseMatrix& pattern, const SolverOptions& options)
    : options_(options) {
  if (options_.solver == LinearSolver::kCholesky || options_.fallback == SolverFallback::kDirect)
    cholesky_ = std::make_unique<CholeskySolver>(pattern);
  if (options_.solver == LinearSolver::kConjugateGradient)
    cg_ = std::make_unique<ConjugateGradientSolver>(pattern, options_.preconditioner,
                                                    options_.max_iterations, options_.tolerance,
                                                    options_.refactor_interval, options_.host);
}

SafeSolver::~SafeSolver() = default;

void SafeSolver::set_limits(int max_iterations, double tolerance, int refactor_interval) {
  options_.max_iterations = max_iterations;
  options_.tolerance = tolerance;
  options_.refactor_interval = refactor_interval;
  if (cg_) cg_->set_limits(max_iterations, tolerance, refactor_interval);
}

SolveReport SafeSolver::solve_direct(const BlockSparseMatrix& a, const double* b, double* x,
                                     bool same_matrix) noexcept {
  SolveReport report;
  report.converged = cholesky_->solve(a, b, x, same_matrix && cholesky_current_);
  cholesky_current_ = report.converged;
  return report;
}

SolveReport SafeSolver::solve(const BlockSparseMatrix& a, const double* b, double* x,
                              bool same_matrix, double residual_floor) noexcept {
  ++counters_.solves;
  if (!same_matrix) cg_current_ = cholesky_current_ = false;
  SolveReport report;
  if (!cg_) {
    report = solve_direct(a, b, x, same_matrix);
  } else if (cholesky_ && direct_hold_ > 0) {  // CG failed lately: do not pay for it to fail again
    --direct_hold_;
    ++counters_.direct_solves_held;
    report = solve_direct(a, b, x, same_matrix);
  } else {
    report = cg_->solve(a, b, x, same_matrix && cg_current_, residual_floor);
    cg_current_ = true;
    counters_.cg_iterations += static_cast<uint64_t>(report.iterations);
    if (report.warm_start_rejected) ++counters_.warm_starts_rejected;
    if (!report.converged && options_.fallback != SolverFallback::kNone) {
      ++counters_.restarts;
      // Restarted from where the first pass got to (dropped for zero when that is worse, as any
      // guess is): a pass that stopped just short of the tolerance, as most do, then ends in a
      // few iterations instead of starting over (the liver demo: 26-30).
      const SolveReport restart =
          cg_->resolve(a, b, x, options_.restart_factor * options_.max_iterations);
      counters_.cg_iterations += static_cast<uint64_t>(restart.iterations);
      report.iterations += restart.iterations;
      report.converged = restart.converged;
      report.relative_residual = restart.relative_residual;
      if (!restart.converged && cholesky_) {
        ++counters_.direct_fallbacks;
        const int iterations = report.iterations;
        report = solve_direct(a, b, x, same_matrix);
        report.iterations = iterations;
        // The next solves go straight to LDL^T, twice as many each time CG fails again.
        direct_hold_ = direct_hold_length_;
        direct_hold_length_ = std::min(2 * direct_hold_length_, kMaxDirectHold);
      }
    } else if (report.converged) {
      direct_hold_length_ = 1;
    }
  }
  if (!report.converged) ++counters_.unconverged;
  counters_.max_relative_residual =
      std::max(counters_.max_relative_residual, report.relative_residual);
  return report;
}

void SafeSolver::state_fields(StateIo& io) {
  io.value(counters_, "solver_counters");
  io.value(direct_hold_, "direct_hold");
  io.value(direct_hold_length_, "direct_hold_length");
  io.value(cg_current_, "cg_current");
  if (io.loading()) cholesky_current_ = false;  // see the header: refactorised on its next use
  if (cg_) cg_->state_fields(io);
}

}  // namespace tacta::models::sparse
