#include "incomplete_cholesky.hpp"

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>

#include "hot_path.hpp"
#include "tacta/models/state_blob.hpp"

namespace tacta::models::sparse {

namespace {
using Block = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
using BlockMap = Eigen::Map<Block>;
using ConstBlockMap = Eigen::Map<const Block>;

// Inverts a symmetric 3x3 block if it is positive definite (leading minors), else false.
bool invert_positive_definite(const double* block, double* inverse) {
  const ConstBlockMap b(block);
  const double m1 = b(0, 0);
  const double m2 = b(0, 0) * b(1, 1) - b(0, 1) * b(1, 0);
  const double m3 = b.determinant();
  if (!(m1 > 0.0 && m2 > 0.0 && m3 > 0.0)) return false;
  BlockMap result(inverse);
  result = b.inverse();
  return true;
}
}  // namespace

BlockIncompleteCholesky::BlockIncompleteCholesky(const BlockSparseMatrix& pattern)
    : node_count_(pattern.node_count()),
      row_starts_(pattern.row_starts().begin(), pattern.row_starts().end()),
      columns_(pattern.columns().begin(), pattern.columns().end()),
      factor_(9 * static_cast<size_t>(pattern.block_count())),
      pivot_inverse_(9 * static_cast<size_t>(node_count_)) {
  update_starts_.reserve(node_count_ + 1);
  update_starts_.push_back(0);
  size_t widest_row = 0;
  for (uint32_t k = 0; k < node_count_; ++k) {
    const uint32_t first = row_starts_[k] + 1, end = row_starts_[k + 1];  // off-diagonal
    widest_row = std::max<size_t>(widest_row, end - first);
    for (uint32_t left = first; left < end; ++left)
      for (uint32_t right = left; right < end; ++right) {
        const uint32_t row = columns_[left], col = columns_[right];  // row < col unless equal
        const auto begin_it = columns_.begin() + row_starts_[row];
        const auto end_it = columns_.begin() + row_starts_[row + 1];
        const auto it = std::lower_bound(begin_it + 1, end_it, col);
        if (row == col)
          updates_.push_back({row_starts_[row], left, right});
        else if (it != end_it && *it == col)
          updates_.push_back({static_cast<uint32_t>(it - columns_.begin()), left, right});
        // else: fill outside the pattern, dropped (the "0" of IC(0))
      }
    update_starts_.push_back(static_cast<uint32_t>(updates_.size()));
  }
  scaled_row_.resize(9 * widest_row);
}

TACTA_HOT_PATH int BlockIncompleteCholesky::factorize(const BlockSparseMatrix& a) {
  const auto values = a.values();
  std::copy(values.begin(), values.end(), factor_.begin());
  int replaced = 0;
  for (uint32_t k = 0; k < node_count_; ++k) {
    const uint32_t diagonal = row_starts_[k];
    double* pivot_inverse = &pivot_inverse_[9 * static_cast<size_t>(k)];
    if (!invert_positive_definite(&factor_[9 * size_t{diagonal}], pivot_inverse)) {
      std::copy_n(&values[9 * size_t{diagonal}], 9, &factor_[9 * size_t{diagonal}]);
      if (!invert_positive_definite(&factor_[9 * size_t{diagonal}], pivot_inverse))
        BlockMap{pivot_inverse}.setIdentity();  // a itself is not SPD there: CG will report it
      ++replaced;
    }
    const ConstBlockMap d_inverse(pivot_inverse);
    const uint32_t first = diagonal + 1;
    for (uint32_t j = first; j < row_starts_[k + 1]; ++j)
      BlockMap(&scaled_row_[9 * size_t{j - first}]).noalias() =
          d_inverse * ConstBlockMap(&factor_[9 * size_t{j}]);
    for (uint32_t u = update_starts_[k]; u < update_starts_[k + 1]; ++u) {
      const Update& update = updates_[u];
      BlockMap(&factor_[9 * size_t{update.target}]).noalias() -=
          ConstBlockMap(&factor_[9 * size_t{update.left}]).transpose() *
          ConstBlockMap(&scaled_row_[9 * size_t{update.right - first}]);
    }
  }
  return replaced;
}

// Scalar on purpose: the forward pass updates z_j that the next rows read back at once, and a
// 4-wide version on the padded layout (as PaddedBlocks) measured slower than these 3-wide
// read-modify-writes.
TACTA_HOT_PATH void BlockIncompleteCholesky::apply(const double* r, double* z) const {
  const size_t n = 4 * static_cast<size_t>(node_count_);
  std::copy_n(r, n, z);
  const double* f = factor_.data();
  // Forward: (D + U)^T w = r, row k of U scattered down as columns of the lower factor.
  for (uint32_t k = 0; k < node_count_; ++k) {
    const double* m = &pivot_inverse_[9 * size_t{k}];
    double* zk = z + 4 * size_t{k};
    const double r0 = zk[0], r1 = zk[1], r2 = zk[2];
    const double w0 = m[0] * r0 + m[1] * r1 + m[2] * r2;
    const double w1 = m[3] * r0 + m[4] * r1 + m[5] * r2;
    const double w2 = m[6] * r0 + m[7] * r1 + m[8] * r2;
    zk[0] = w0;
    zk[1] = w1;
    zk[2] = w2;
    for (uint32_t j = row_starts_[k] + 1; j < row_starts_[k + 1]; ++j) {
      const double* b = f + 9 * size_t{j};
      double* zj = z + 4 * size_t{columns_[j]};
      zj[0] -= b[0] * w0 + b[3] * w1 + b[6] * w2;
      zj[1] -= b[1] * w0 + b[4] * w1 + b[7] * w2;
      zj[2] -= b[2] * w0 + b[5] * w1 + b[8] * w2;
    }
  }
  // Backward: (D + U) z = D w, i.e. z_i = w_i - D_i^-1 sum_{j > i} U_ij z_j.
  for (uint32_t i = node_count_; i-- > 0;) {
    double s0 = 0.0, s1 = 0.0, s2 = 0.0;
    for (uint32_t j = row_starts_[i] + 1; j < row_starts_[i + 1]; ++j) {
      const double* b = f + 9 * size_t{j};
      const double* zj = z + 4 * size_t{columns_[j]};
      s0 += b[0] * zj[0] + b[1] * zj[1] + b[2] * zj[2];
      s1 += b[3] * zj[0] + b[4] * zj[1] + b[5] * zj[2];
      s2 += b[6] * zj[0] + b[7] * zj[1] + b[8] * zj[2];
    }
    const double* m = &pivot_inverse_[9 * size_t{i}];
    double* zi = z + 4 * size_t{i};
    zi[0] -= m[0] * s0 + m[1] * s1 + m[2] * s2;
    zi[1] -= m[3] * s0 + m[4] * s1 + m[5] * s2;
    zi[2] -= m[6] * s0 + m[7] * s1 + m[8] * s2;
  }
}

void BlockIncompleteCholesky::state_fields(StateIo& io) {
  io.vector(factor_, "ic_factor");
  io.vector(pivot_inverse_, "ic_pivot_inverse");
}

}  // namespace tacta::models::sparse
