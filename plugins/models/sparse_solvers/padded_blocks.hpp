// A copy of a BlockSparseMatrix's values with each 3x3 block stored as three rows of four (the
// fourth a zero), for vectors that hold 4 values per node (the fourth 0): a block row and a
// node are each one 4-wide vector, aligned to the node, so the loops below become vector
// instructions (AVX2 in the x86-64-v3 clone, SSE2 pairs otherwise) and a store never half
// overlaps a later load (which stalls store forwarding).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "block_sparse.hpp"

namespace tacta::models {
class StateIo;
}

namespace tacta::models::sparse {

class PaddedBlocks {
 public:
  explicit PaddedBlocks(const BlockSparseMatrix& pattern);
  // Copies 9-per-block row-major values (the pattern's layout) in.
  void assign(std::span<const double> values);
  // The same for the blocks of rows [begin, end) only.
  void assign_rows(std::span<const double> values, uint32_t begin, uint32_t end);
  // y = A x for the symmetric matrix whose upper blocks these are (4 per node); returns x . y.
  double multiply_symmetric(const double* x, double* y) const;
  // Rows [begin, end) of y = A q, both triangles read (nothing written outside those rows, so
  // row ranges can run on different threads); returns the rows' q . y. q = x, or with z given
  // q = z + beta x, formed on the fly for every block (CG's direction update fused into the
  // product: no pass and no wait between them) and written to q_out for rows [begin, end).
  double multiply_rows(const double* x, double* y, uint32_t begin, uint32_t end,
                       const double* z = nullptr, double beta = 0.0, double* q_out = nullptr) const;
  // Checkpoints (state_blob.hpp): the values, which a kept preconditioner reuses.
  void state_fields(StateIo& io);

 private:
  uint32_t node_count_;
  std::vector<uint32_t> row_starts_, columns_;
  std::vector<uint32_t> lower_starts_, lower_blocks_, lower_rows_;  // see BlockSparseMatrix
  std::vector<double> values_;                                      // 12 per block
};

}  // namespace tacta::models::sparse
