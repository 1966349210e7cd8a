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

namespace tacta::models::sparse {

class PaddedBlocks {
 public:
  explicit PaddedBlocks(const BlockSparseMatrix& pattern);
  // Copies 9-per-block row-major values (the pattern's layout) in.
  void assign(std::span<const double> values);
  // y = A x for the symmetric matrix whose upper blocks these are (4 per node); returns x . y.
  double multiply_symmetric(const double* x, double* y) const;

 private:
  uint32_t node_count_;
  std::vector<uint32_t> row_starts_, columns_;
  std::vector<double> values_;  // 12 per block
};

}  // namespace tacta::models::sparse
