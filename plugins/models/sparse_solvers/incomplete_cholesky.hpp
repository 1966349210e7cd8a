// Block incomplete Cholesky with no fill, IC(0), on a BlockSparseMatrix: the CG preconditioner
//   M = (D + U)^T D^-1 (D + U) ~ A,
// D block diagonal (3x3 pivots), U strictly upper with exactly A's pattern; every update that
// would land outside the pattern is dropped. The update list (which block receives which
// product) is built once at creation, so factorize() and apply() allocate nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "block_sparse.hpp"

namespace tacta::models {
class StateIo;
}

namespace tacta::models::sparse {

class BlockIncompleteCholesky {
 public:
  explicit BlockIncompleteCholesky(const BlockSparseMatrix& pattern);

  // Factorises a (same pattern as at creation). A pivot that is not positive definite (IC(0)
  // can break down on matrices that are not M-matrices) is replaced by a's own diagonal block,
  // which keeps M symmetric positive definite; returns how many pivots were replaced.
  int factorize(const BlockSparseMatrix& a);
  // z = M^-1 r (forward then backward block substitution), 4 values per node (the fourth 0,
  // see PaddedBlocks).
  void apply(const double* r, double* z) const;
  // Checkpoints (state_blob.hpp): the factor, which may be older than the matrix being solved.
  void state_fields(StateIo& io);

 private:
  struct Update {  // w[target] -= w[left]^T Dinv_k w[right], left and right in row k
    uint32_t target, left, right;
  };
  uint32_t node_count_;
  std::vector<uint32_t> row_starts_, columns_;  // a copy of the pattern
  std::vector<uint32_t> update_starts_;         // per row k: its updates in updates_
  std::vector<Update> updates_;
  std::vector<double> factor_;         // 9 per block: D on the diagonal, U off it
  std::vector<double> pivot_inverse_;  // 9 per node: D^-1
  std::vector<double> scaled_row_;     // D_k^-1 U_kj for the row being eliminated
};

}  // namespace tacta::models::sparse
