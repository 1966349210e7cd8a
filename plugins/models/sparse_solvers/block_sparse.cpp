#include "block_sparse.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "hot_path.hpp"

namespace tacta::models::sparse {

BlockSparseMatrix::BlockSparseMatrix(uint32_t node_count, std::span<const uint32_t> tets,
                                     std::span<const uint32_t> extra_pairs)
    : node_count_(node_count) {
  // Every pair (i, j >= i) that shares an element, the diagonal and the extra pairs, gathered
  // row by row in one array (a count, then a fill), then each row sorted without duplicates.
  const auto for_each_pair = [&](auto&& add) {
    for (uint32_t i = 0; i < node_count; ++i) add(i, i);
    for (size_t e = 0; e + 3 < tets.size(); e += 4)
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          if (tets[e + a] < tets[e + b]) add(tets[e + a], tets[e + b]);
    for (size_t p = 0; p + 1 < extra_pairs.size(); p += 2)
      add(std::min(extra_pairs[p], extra_pairs[p + 1]),
          std::max(extra_pairs[p], extra_pairs[p + 1]));
  };
  std::vector<uint32_t> start(size_t{node_count} + 1, 0);
  for_each_pair([&](uint32_t i, uint32_t) { ++start[i + 1]; });
  for (uint32_t i = 0; i < node_count; ++i) start[i + 1] += start[i];
  std::vector<uint32_t> pairs(start.back());
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for_each_pair([&](uint32_t i, uint32_t j) { pairs[fill[i]++] = j; });
  }
  row_starts_.resize(node_count + 1, 0);
  uint32_t kept = 0;  // pairs[0, kept): the rows done, compacted
  for (uint32_t i = 0; i < node_count; ++i) {
    const auto begin = pairs.begin() + start[i], end = pairs.begin() + start[i + 1];
    std::sort(begin, end);
    const auto last = std::unique(begin, end);
    for (auto j = begin; j != last; ++j) pairs[kept++] = *j;
    row_starts_[i + 1] = kept;
  }
  columns_.assign(pairs.begin(), pairs.begin() + kept);
  static constexpr int kPairA[10] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3};
  static constexpr int kPairB[10] = {0, 1, 2, 3, 1, 2, 3, 2, 3, 3};
  const size_t element_count = tets.size() / 4;
  element_slots_.resize(10 * element_count);
  for (size_t e = 0; e < element_count; ++e)
    for (int p = 0; p < 10; ++p) {
      const uint32_t i = tets[4 * e + kPairA[p]], j = tets[4 * e + kPairB[p]];
      element_slots_[10 * e + p] = block_index(std::min(i, j), std::max(i, j));
    }
  values_.assign(9 * static_cast<size_t>(columns_.size()), 0.0);
  // The transposed view: for each column i, the off-diagonal blocks (j, i), j ascending.
  lower_starts_.assign(node_count + 1, 0);
  for (uint32_t k = 0; k < columns_.size(); ++k) ++lower_starts_[columns_[k] + 1];
  for (uint32_t i = 0; i < node_count; ++i)
    lower_starts_[i + 1] += lower_starts_[i] - 1;  // less the diagonal block
  lower_blocks_.resize(lower_starts_.back());
  lower_rows_.resize(lower_starts_.back());
  std::vector<uint32_t> next(lower_starts_.begin(), lower_starts_.end() - 1);
  for (uint32_t j = 0; j < node_count; ++j)
    for (uint32_t k = row_starts_[j] + 1; k < row_starts_[j + 1]; ++k) {
      const uint32_t at = next[columns_[k]]++;
      lower_blocks_[at] = k;
      lower_rows_[at] = j;
    }
}

uint32_t BlockSparseMatrix::block_index(uint32_t row, uint32_t col) const {
  const auto begin = columns_.begin() + row_starts_[row];
  const auto end = columns_.begin() + row_starts_[row + 1];
  const auto it = std::lower_bound(begin, end, col);
  if (it == end || *it != col)
    throw std::logic_error("block (" + std::to_string(row) + ", " + std::to_string(col) +
                           ") is not in the sparsity pattern");
  return static_cast<uint32_t>(it - columns_.begin());
}

void BlockSparseMatrix::set_zero() { std::fill(values_.begin(), values_.end(), 0.0); }

TACTA_HOT_PATH double BlockSparseMatrix::multiply(const double* x, double* y, size_t stride) const {
  const double* v = values_.data();
  double x_dot_y = 0.0;
  std::fill_n(y, stride * node_count_, 0.0);
  for (uint32_t i = 0; i < node_count_; ++i) {
    const double* xi = x + stride * i;
    const double x0 = xi[0], x1 = xi[1], x2 = xi[2];
    const uint32_t first = row_starts_[i];
    const double* d = v + 9 * static_cast<size_t>(first);  // diagonal block
    double y0 = d[0] * x0 + d[1] * x1 + d[2] * x2;
    double y1 = d[3] * x0 + d[4] * x1 + d[5] * x2;
    double y2 = d[6] * x0 + d[7] * x1 + d[8] * x2;
    for (uint32_t k = first + 1; k < row_starts_[i + 1]; ++k) {
      const double* b = v + 9 * static_cast<size_t>(k);
      const size_t j = stride * columns_[k];
      const double* xj = x + j;
      y0 += b[0] * xj[0] + b[1] * xj[1] + b[2] * xj[2];
      y1 += b[3] * xj[0] + b[4] * xj[1] + b[5] * xj[2];
      y2 += b[6] * xj[0] + b[7] * xj[1] + b[8] * xj[2];
      double* yj = y + j;  // the mirrored block (j, i) = B^T
      yj[0] += b[0] * x0 + b[3] * x1 + b[6] * x2;
      yj[1] += b[1] * x0 + b[4] * x1 + b[7] * x2;
      yj[2] += b[2] * x0 + b[5] * x1 + b[8] * x2;
    }
    // Rows above i have scattered into y_i already: with this row's part it is complete.
    double* yi = y + stride * i;
    y0 += yi[0];
    y1 += yi[1];
    y2 += yi[2];
    yi[0] = y0;
    yi[1] = y1;
    yi[2] = y2;
    x_dot_y += x0 * y0 + x1 * y1 + x2 * y2;
  }
  return x_dot_y;
}

TACTA_HOT_PATH double BlockSparseMatrix::multiply_rows(const double* x, double* y, uint32_t begin,
                                                       uint32_t end, size_t stride) const {
  const double* v = values_.data();
  double x_dot_y = 0.0;
  for (uint32_t i = begin; i < end; ++i) {
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    for (uint32_t m = lower_starts_[i]; m < lower_starts_[i + 1]; ++m) {  // B^T x_j
      const double* b = v + 9 * size_t{lower_blocks_[m]};
      const double* xj = x + stride * lower_rows_[m];
      y0 += b[0] * xj[0] + b[3] * xj[1] + b[6] * xj[2];
      y1 += b[1] * xj[0] + b[4] * xj[1] + b[7] * xj[2];
      y2 += b[2] * xj[0] + b[5] * xj[1] + b[8] * xj[2];
    }
    for (uint32_t k = row_starts_[i]; k < row_starts_[i + 1]; ++k) {  // B x_j, diagonal first
      const double* b = v + 9 * size_t{k};
      const double* xj = x + stride * columns_[k];
      y0 += b[0] * xj[0] + b[1] * xj[1] + b[2] * xj[2];
      y1 += b[3] * xj[0] + b[4] * xj[1] + b[5] * xj[2];
      y2 += b[6] * xj[0] + b[7] * xj[1] + b[8] * xj[2];
    }
    double* yi = y + stride * i;
    yi[0] = y0;
    yi[1] = y1;
    yi[2] = y2;
    for (size_t c = 3; c < stride; ++c) yi[c] = 0.0;
    const double* xi = x + stride * i;
    x_dot_y += xi[0] * y0 + xi[1] * y1 + xi[2] * y2;
  }
  return x_dot_y;
}

void BlockSparseMatrix::zero_rows(uint32_t begin, uint32_t end) {
  std::fill(values_.begin() + 9 * std::ptrdiff_t{row_starts_[begin]},
            values_.begin() + 9 * std::ptrdiff_t{row_starts_[end]}, 0.0);
}

void BlockSparseMatrix::finish_rows(uint32_t begin, uint32_t end, std::span<const double> values,
                                    double scale, std::span<const uint8_t> fixed) {
  for (uint32_t i = begin; i < end; ++i) {
    double* d = block(diagonal_block(i));
    if (!fixed.empty() && fixed[i]) {
      std::fill_n(d, 9, 0.0);
      d[0] = d[4] = d[8] = 1.0;
    } else {
      d[0] += scale * values[i];
      d[4] += scale * values[i];
      d[8] += scale * values[i];
    }
    if (fixed.empty()) continue;
    for (uint32_t k = row_starts_[i] + 1; k < row_starts_[i + 1]; ++k)
      if (fixed[i] || fixed[columns_[k]]) std::fill_n(block(k), 9, 0.0);
  }
}

void BlockSparseMatrix::apply_fixed(std::span<const uint8_t> fixed) {
  if (fixed.empty()) return;
  if (!fixed_built_) {  // first call (at creation): list the blocks to clear once
    for (uint32_t i = 0; i < node_count_; ++i)
      for (uint32_t k = row_starts_[i]; k < row_starts_[i + 1]; ++k)
        if (columns_[k] != i && (fixed[i] || fixed[columns_[k]])) fixed_offdiagonal_.push_back(k);
    fixed_built_ = true;
  }
  for (uint32_t k : fixed_offdiagonal_) std::fill_n(block(k), 9, 0.0);
  for (uint32_t i = 0; i < node_count_; ++i) {
    if (!fixed[i]) continue;
    double* d = block(diagonal_block(i));
    std::fill_n(d, 9, 0.0);
    d[0] = d[4] = d[8] = 1.0;
  }
}

void BlockSparseMatrix::add_to_diagonal(std::span<const double> values, double scale) {
  for (uint32_t i = 0; i < node_count_; ++i) {
    double* d = block(diagonal_block(i));
    d[0] += scale * values[i];
    d[4] += scale * values[i];
    d[8] += scale * values[i];
  }
}

}  // namespace tacta::models::sparse
