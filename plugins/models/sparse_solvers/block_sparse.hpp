// A symmetric matrix of 3x3 blocks in compressed rows (block CSR), upper triangle only: row i
// holds blocks (i, j) with j >= i, the diagonal first. Half the storage of a full matrix, so
// the conjugate-gradient products read half the memory. The pattern is fixed at creation:
// every element's 10 node pairs map to precomputed slots, so a step refills values in place
// and never allocates.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tacta::models::sparse {

class BlockSparseMatrix {
 public:
  // tets: 4 node indices per element. Builds the pattern of all node pairs that share a tet,
  // plus extra_pairs (2 node indices each; terms that couple nodes beyond one element).
  BlockSparseMatrix(uint32_t node_count, std::span<const uint32_t> tets,
                    std::span<const uint32_t> extra_pairs = {});

  uint32_t node_count() const { return node_count_; }
  uint32_t block_count() const { return static_cast<uint32_t>(columns_.size()); }
  // Index of block (row, col), row <= col, in the block arrays; the pair must share an element.
  uint32_t block_index(uint32_t row, uint32_t col) const;
  uint32_t diagonal_block(uint32_t node) const { return row_starts_[node]; }
  // Slots of element e's node pairs (a, b), a <= b in 0..3, in the order (0,0) (0,1) (0,2)
  // (0,3) (1,1) (1,2) (1,3) (2,2) (2,3) (3,3): the stored block is (min node, max node).
  const uint32_t* element_slots(uint32_t element) const { return &element_slots_[10 * element]; }

  double* block(uint32_t index) { return &values_[9 * static_cast<size_t>(index)]; }
  const double* block(uint32_t index) const { return &values_[9 * static_cast<size_t>(index)]; }
  std::span<double> values() { return values_; }
  std::span<const double> values() const { return values_; }
  std::span<const uint32_t> row_starts() const { return row_starts_; }
  std::span<const uint32_t> columns() const { return columns_; }
  // The lower triangle of row i, read from the upper storage: blocks (j, i), j < i, by j
  // (stored as (j, i); the row's block is its transpose). lower_starts() has node_count + 1.
  std::span<const uint32_t> lower_starts() const { return lower_starts_; }
  std::span<const uint32_t> lower_blocks() const { return lower_blocks_; }
  std::span<const uint32_t> lower_rows() const { return lower_rows_; }

  void set_zero();
  // y = A x (the lower triangle applied as the transpose of the upper), x and y with `stride`
  // values per node of which the first 3 count (y's others set to 0). Returns x . y, summed as
  // each row completes (CG's p . Ap without another pass).
  double multiply(const double* x, double* y, size_t stride = 3) const;
  // Rows [begin, end) of y = A x, reading both triangles (the lower one through lower_*), so
  // nothing outside those rows is written and row ranges can run on different threads. Equal to
  // multiply() to rounding. Returns the rows' x . y.
  double multiply_rows(const double* x, double* y, uint32_t begin, uint32_t end,
                       size_t stride = 3) const;
  // The blocks of rows [begin, end) (blocks (i, j), j >= i) set to zero.
  void zero_rows(uint32_t begin, uint32_t end);
  // add_to_diagonal then apply_fixed (after a first apply_fixed has run), for the blocks of
  // rows [begin, end) only; the same values, bit for bit.
  void finish_rows(uint32_t begin, uint32_t end, std::span<const double> values, double scale,
                   std::span<const uint8_t> fixed);
  // Adds scale * values[i] * I to each node's diagonal block (a lumped mass matrix).
  void add_to_diagonal(std::span<const double> values, double scale);
  // Makes fixed nodes' rows and columns identity (zero off-diagonal, I on the diagonal).
  void apply_fixed(std::span<const uint8_t> fixed);

 private:
  uint32_t node_count_;
  std::vector<uint32_t> row_starts_;  // node_count + 1
  std::vector<uint32_t> columns_;     // block column per block, sorted, diagonal first
  std::vector<uint32_t> element_slots_;
  std::vector<uint32_t> lower_starts_, lower_blocks_, lower_rows_;
  std::vector<double> values_;               // 9 per block, row-major
  std::vector<uint32_t> fixed_offdiagonal_;  // blocks touching a fixed node, off the diagonal
  bool fixed_built_ = false;
};

}  // namespace tacta::models::sparse
