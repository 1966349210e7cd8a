// A symmetric matrix of 3x3 blocks in compressed rows (block CSR, both triangles stored), with a
// pattern fixed at creation: every element's 4x4 block entries map to precomputed slots, so a
// step refills values in place and never allocates.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace tacta::models::corotational {

class BlockSparseMatrix {
 public:
  // tets: 4 node indices per element. Builds the pattern of all node pairs that share a tet.
  BlockSparseMatrix(uint32_t node_count, std::span<const uint32_t> tets);

  uint32_t node_count() const { return node_count_; }
  uint32_t block_count() const { return static_cast<uint32_t>(columns_.size()); }
  // Index of block (row, col) in the block arrays; the pair must share an element.
  uint32_t block_index(uint32_t row, uint32_t col) const;
  uint32_t diagonal_block(uint32_t node) const { return diagonal_[node]; }
  // Slot of block (a, b) of element e (a, b in 0..3): 16 per element, row-major in (a, b).
  const uint32_t* element_slots(uint32_t element) const { return &element_slots_[16 * element]; }

  double* block(uint32_t index) { return &values_[9 * static_cast<size_t>(index)]; }
  const double* block(uint32_t index) const { return &values_[9 * static_cast<size_t>(index)]; }
  std::span<double> values() { return values_; }
  std::span<const double> values() const { return values_; }
  std::span<const uint32_t> row_starts() const { return row_starts_; }
  std::span<const uint32_t> columns() const { return columns_; }

  void set_zero();
  // y = A x, both 3 per node.
  void multiply(const double* x, double* y) const;
  // Makes fixed nodes' rows and columns identity (zero off-diagonal, I on the diagonal).
  void apply_fixed(std::span<const uint8_t> fixed);

 private:
  uint32_t node_count_;
  std::vector<uint32_t> row_starts_;  // node_count + 1
  std::vector<uint32_t> columns_;     // block column per block, sorted within a row
  std::vector<uint32_t> diagonal_;    // block index of (i, i)
  std::vector<uint32_t> element_slots_;
  std::vector<double> values_;        // 9 per block, row-major
  std::vector<uint32_t> fixed_offdiagonal_;  // blocks touching a fixed node, off the diagonal
  bool fixed_built_ = false;
};

}  // namespace tacta::models::corotational
