// The implicit models' linear solve with its safety net: preconditioned CG that checks its
// residual, and when it has not converged restarts (from its last iterate, or from zero when that
// is worse) with more iterations, then solves with sparse LDL^T and keeps using LDL^T for a
// doubling number of solves (CG failing once on a system tends to fail again). A capped CG
// accepted unconverged lets errors pile up: SOFA's cantilever collapsed at 0.44 s that way.
// Counts everything for report.json.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "linear_solvers.hpp"
#include "tacta/model_api.h"

namespace tacta::models::sparse {

enum class LinearSolver { kConjugateGradient = 0, kCholesky = 1 };
// What CG does when a solve has not converged within max_iterations.
enum class SolverFallback { kDirect = 0, kRestartOnly = 1, kNone = 2 };

struct SolverOptions {
  LinearSolver solver = LinearSolver::kConjugateGradient;
  Preconditioner preconditioner = Preconditioner::kBlockJacobi;
  int max_iterations = 25;    // CG iterations per solve
  double tolerance = 1e-5;    // CG: relative residual ||b - A x|| / ||b||
  int refactor_interval = 1;  // incomplete Cholesky: solves between refactorisations
  SolverFallback fallback = SolverFallback::kDirect;
  int restart_factor = 8;  // the restart's cap, in units of max_iterations
  // The engine's workers (model_api.h), or null: a (block) Jacobi CG on a body of
  // ConjugateGradientSolver::kMinThreadedNodes or more runs on them when there are two or more.
  const tacta_host_services* host = nullptr;
};

// Counts since creation.
struct SolverCounters {
  uint64_t solves = 0;
  uint64_t cg_iterations = 0;          // every pass included
  uint64_t warm_starts_rejected = 0;   // the caller's guess was worse than zero
  uint64_t restarts = 0;               // CG not converged: restarted, more iterations
  uint64_t direct_fallbacks = 0;       // still not converged: sparse LDL^T solved it
  uint64_t direct_solves_held = 0;     // solves sent straight to LDL^T after a recent fallback
  uint64_t unconverged = 0;            // solves left with a residual above the tolerance
  double max_relative_residual = 0.0;  // of the accepted solutions
};

// The counters as report.json names them.
std::array<tacta_model_counter, 8> named_counters(const SolverCounters& counters);

class SafeSolver {
 public:
  // Builds every buffer for matrices of this pattern (LDL^T's analysis too unless fallback is
  // kRestartOnly or kNone with CG).
  SafeSolver(const BlockSparseMatrix& pattern, const SolverOptions& options);
  ~SafeSolver();
  // x: the initial guess on entry (CG only), the solution on exit. No allocation (see
  // CholeskySolver for its one exception on very large systems). same_matrix: a is the matrix
  // of the last solve, unchanged, so its preconditioner (or LDL^T factor) is reused.
  // residual_floor: CG's tolerance is relative to max(||b||, residual_floor)
  // (ConjugateGradientSolver::solve).
  SolveReport solve(const BlockSparseMatrix& a, const double* b, double* x,
                    bool same_matrix = false, double residual_floor = 0.0) noexcept;
  void set_limits(int max_iterations, double tolerance, int refactor_interval);
  const SolverOptions& options() const { return options_; }
  const SolverCounters& counters() const { return counters_; }
  bool iterative() const { return cg_ != nullptr; }
  // Checkpoints (state_blob.hpp): the counters, the LDL^T hold, and what CG keeps between
  // solves. The LDL^T factor is not saved: a load marks it stale, and refactorising the same
  // matrix gives the same factor, bit for bit.
  void state_fields(StateIo& io);

 private:
  SolveReport solve_direct(const BlockSparseMatrix& a, const double* b, double* x,
                           bool same_matrix) noexcept;
  SolverOptions options_;
  std::unique_ptr<ConjugateGradientSolver> cg_;
  std::unique_ptr<CholeskySolver> cholesky_;
  SolverCounters counters_;
  int direct_hold_ = 0, direct_hold_length_ = 1;  // solves left on LDL^T; the next hold's length
  bool cg_current_ = false, cholesky_current_ = false;  // built from the last solve's matrix
};

}  // namespace tacta::models::sparse
