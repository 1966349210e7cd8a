// Linear solvers for the implicit step A dv = b on a BlockSparseMatrix: warm-started
// preconditioned conjugate gradients, and sparse LDL^T (Eigen) whose symbolic analysis is done
// once. Both keep every buffer from creation, so solve() allocates nothing (see the note on
// CholeskySolver for the one exception).
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "block_sparse.hpp"
#include "incomplete_cholesky.hpp"
#include "padded_blocks.hpp"
#include "row_team.hpp"

namespace tacta::models::sparse {

enum class Preconditioner { kJacobi = 0, kBlockJacobi = 1, kIncompleteCholesky = 2 };

struct SolveReport {
  int iterations = 0;
  bool converged = true;
  // ||b - A x|| / max(||b||, the solve's residual_floor) at exit (CG's recurrence residual)
  double relative_residual = 0.0;
  int replaced_pivots = 0;           // IC(0) pivots replaced by A's diagonal block
  bool warm_start_rejected = false;  // ||b - A x0|| > ||b||: CG started from zero instead
};

class ConjugateGradientSolver {
 public:
  // Nodes from which a solve runs on the host's workers (when it offers two or more).
  static constexpr uint32_t kMinThreadedNodes = 384;

  // refactor_interval: with incomplete Cholesky, solves between refactorisations (1: every
  // solve); the first solve always factorises. host: with two or more workers and
  // kMinThreadedNodes nodes, a (block) Jacobi solve runs on them (row chunks, RowTeam): the
  // preconditioner's build, the products, the updates and the dot products; IC(0) stays serial
  // (its triangular solves are a chain from the first row to the last).
  ConjugateGradientSolver(const BlockSparseMatrix& pattern, Preconditioner preconditioner,
                          int max_iterations, double tolerance, int refactor_interval = 1,
                          const tacta_host_services* host = nullptr);
  // x holds the initial guess (the previous step's solution) and receives the solution.
  // Convergence: ||b - A x|| <= tolerance max(||b||, residual_floor). The floor is the scale b's
  // terms have before they cancel (an implicit step near equilibrium: forces that balance leave
  // a b far smaller than any of them, and a tolerance on ||b|| alone asks for digits that
  // describe nothing). keep_preconditioner: a is the last solve's matrix, unchanged.
  SolveReport solve(const BlockSparseMatrix& a, const double* b, double* x,
                    bool keep_preconditioner = false, double residual_floor = 0.0);
  // Solves again with the preconditioner and floor of the last solve() on the same a, at most
  // max_iterations: the fallback when solve() did not converge.
  SolveReport resolve(const BlockSparseMatrix& a, const double* b, double* x, int max_iterations) {
    return iterate(a, b, x, max_iterations);
  }
  bool threaded() const { return team_.threaded(); }
  // Checkpoints (state_blob.hpp): the preconditioner the next solve may keep, and the
  // refactorisation count.
  void state_fields(StateIo& io);
  void set_limits(int max_iterations, double tolerance, int refactor_interval) {
    max_iterations_ = max_iterations;
    tolerance_ = tolerance;
    refactor_interval_ = std::max(1, refactor_interval);
    solves_since_factor_ %= refactor_interval_;
  }

 private:
  void build_preconditioner(const BlockSparseMatrix& a);
  // The (block) Jacobi inverse of the diagonal blocks of nodes [begin, end).
  void invert_diagonal(const BlockSparseMatrix& a, uint32_t begin, uint32_t end);
  SolveReport iterate(const BlockSparseMatrix& a, const double* b, double* x, int max_iterations);
  // iterate() on the host's workers: two waits per iteration (the product with p . Ap, then
  // the update with r . r and r . z), the direction update fused into the next product.
  SolveReport iterate_threaded(const double* b, double* x, int max_iterations);
  void apply_preconditioner(const double* r, double* z) const;
  // y = A x on 4-per-node vectors, returns x . y.
  double multiply(const BlockSparseMatrix& a, const double* x, double* y) const;
  // x += alpha p, r -= alpha Ap, z = M^-1 r; returns (r.r, r.z) in one pass where M allows.
  // z is skipped (r.z returned as 0) when r.r <= converged_norm2 and M is not fused.
  std::pair<double, double> update(double alpha, double converged_norm2);
  // update()'s (block) Jacobi pass over nodes [begin, end): x, r and z, returns (r.r, r.z).
  std::pair<double, double> update_rows(double alpha, size_t begin, size_t end);
  Preconditioner preconditioner_;
  int max_iterations_;
  double tolerance_;
  double residual_floor_ = 0.0;  // the last solve()'s
  int refactor_interval_, solves_since_factor_ = 0;
  int replaced_pivots_ = 0;
  std::unique_ptr<BlockIncompleteCholesky> incomplete_cholesky_;
  // (Block) Jacobi: the inverse diagonal block per node as 3 columns of 4 (the fourth 0), so
  // z_i = r_i0 col0 + r_i1 col1 + r_i2 col2 is 4-wide.
  std::vector<double> inverse_columns_;
  // CG's vectors hold 4 values per node (the fourth 0), the layout PaddedBlocks works in;
  // b and x arrive with 3 and are converted at the solve's start and end.
  std::vector<double> x_, r_, z_, p_, ap_;
  std::vector<double> p_next_;  // threaded: the direction the fused product writes
  PaddedBlocks padded_;         // A for the products, refreshed at each solve
  RowTeam team_;
};

// Eigen's LDL^T with an AMD ordering computed here once, so the matrix handed to the numeric
// factorisation is already permuted and no per-step reordering copy is made. Eigen still keeps
// its work arrays on the stack only below EIGEN_STACK_ALLOCATION_LIMIT (128 KiB: about 16k
// unknowns); beyond that its factorisation allocates.
class CholeskySolver {
 public:
  explicit CholeskySolver(const BlockSparseMatrix& pattern);
  ~CholeskySolver();
  // Factorises a (numeric only) and solves; false if the matrix is not positive definite.
  // keep_factor: a is the matrix of the last successful solve, unchanged (no refactorisation).
  bool solve(const BlockSparseMatrix& a, const double* b, double* x, bool keep_factor = false);

 private:
  struct Ldlt;
  std::unique_ptr<Ldlt> ldlt_;
  Eigen::SparseMatrix<double, Eigen::ColMajor, int> permuted_upper_;
  std::vector<uint32_t> value_source_;  // per stored entry: index into the block values
  std::vector<int> new_index_;          // unknown -> permuted unknown
  Eigen::VectorXd rhs_, solution_;
};

}  // namespace tacta::models::sparse
