#include "padded_blocks.hpp"

#include <algorithm>
#include <cstring>

#include "hot_path.hpp"
#include "lanes4.hpp"
#include "tacta/models/state_blob.hpp"

namespace tacta::models::sparse {

namespace {

// A stored block's three rows, each padded to 4 lanes.
inline void load_block(const double* b, Lanes4& b0, Lanes4& b1, Lanes4& b2) {
  std::memcpy(&b0, b, sizeof b0);
  std::memcpy(&b1, b + 4, sizeof b1);
  std::memcpy(&b2, b + 8, sizeof b2);
}

// The direction at padded offset j: x_j, or with CG's update fused in, z_j + beta x_j.
// (Vectors by reference: by value they would change the calling convention without AVX.)
inline void direction_at(const double* x, const double* z, const Lanes4& beta4, size_t j,
                         Lanes4& out) {
  std::memcpy(&out, x + j, sizeof out);
  if (z == nullptr) return;
  Lanes4 zj;
  std::memcpy(&zj, z + j, sizeof zj);
  out = zj + beta4 * out;
}

}  // namespace

PaddedBlocks::PaddedBlocks(const BlockSparseMatrix& pattern)
    : node_count_(pattern.node_count()),
      row_starts_(pattern.row_starts().begin(), pattern.row_starts().end()),
      columns_(pattern.columns().begin(), pattern.columns().end()),
      lower_starts_(pattern.lower_starts().begin(), pattern.lower_starts().end()),
      lower_blocks_(pattern.lower_blocks().begin(), pattern.lower_blocks().end()),
      lower_rows_(pattern.lower_rows().begin(), pattern.lower_rows().end()),
      values_(12 * size_t{pattern.block_count()}, 0.0) {}

TACTA_HOT_PATH void PaddedBlocks::assign(std::span<const double> values) {
  const size_t blocks = values_.size() / 12;
  for (size_t k = 0; k < blocks; ++k)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) values_[12 * k + 4 * r + c] = values[9 * k + 3 * r + c];
}

TACTA_HOT_PATH void PaddedBlocks::assign_rows(std::span<const double> values, uint32_t begin,
                                              uint32_t end) {
  for (size_t k = row_starts_[begin]; k < row_starts_[end]; ++k)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) values_[12 * k + 4 * r + c] = values[9 * k + 3 * r + c];
}

TACTA_HOT_PATH double PaddedBlocks::multiply_rows(const double* __restrict x, double* __restrict y,
                                                  uint32_t begin, uint32_t end,
                                                  const double* __restrict z, double beta,
                                                  double* __restrict q_out) const {
  const double* v = values_.data();
  const Lanes4 beta4 = TACTA_SPLAT4(beta);
  double q_dot_y = 0.0;
  for (uint32_t i = begin; i < end; ++i) {
    // The lower blocks (j, i) of row i are stored as (j, i): their transposes times q_j, 4-wide.
    Lanes4 lower = TACTA_SPLAT4(0.0);
    for (uint32_t m = lower_starts_[i]; m < lower_starts_[i + 1]; ++m) {
      Lanes4 b0, b1, b2, qj;
      load_block(v + 12 * size_t{lower_blocks_[m]}, b0, b1, b2);
      direction_at(x, z, beta4, 4 * size_t{lower_rows_[m]}, qj);
      lower += TACTA_SPLAT4(qj[0]) * b0 + TACTA_SPLAT4(qj[1]) * b1 + TACTA_SPLAT4(qj[2]) * b2;
    }
    // The upper blocks, diagonal first: acc_r holds row r of each block times q_j, by lane.
    Lanes4 acc0 = TACTA_SPLAT4(0.0), acc1 = acc0, acc2 = acc0;
    for (uint32_t k = row_starts_[i]; k < row_starts_[i + 1]; ++k) {
      Lanes4 b0, b1, b2, qj;
      load_block(v + 12 * size_t{k}, b0, b1, b2);
      direction_at(x, z, beta4, 4 * size_t{columns_[k]}, qj);
      acc0 += b0 * qj;
      acc1 += b1 * qj;
      acc2 += b2 * qj;
    }
    double* yi = y + 4 * size_t{i};
    yi[0] = lower[0] + ((acc0[0] + acc0[1]) + (acc0[2] + acc0[3]));
    yi[1] = lower[1] + ((acc1[0] + acc1[1]) + (acc1[2] + acc1[3]));
    yi[2] = lower[2] + ((acc2[0] + acc2[1]) + (acc2[2] + acc2[3]));
    yi[3] = 0.0;
    Lanes4 qi;
    std::memcpy(&qi, x + 4 * size_t{i}, sizeof qi);
    if (z != nullptr) {
      Lanes4 zi;
      std::memcpy(&zi, z + 4 * size_t{i}, sizeof zi);
      qi = zi + beta4 * qi;
      std::memcpy(q_out + 4 * size_t{i}, &qi, sizeof qi);
    }
    q_dot_y += qi[0] * yi[0] + qi[1] * yi[1] + qi[2] * yi[2];
  }
  return q_dot_y;
}

TACTA_HOT_PATH double PaddedBlocks::multiply_symmetric(const double* __restrict x,
                                                       double* __restrict y) const {
  std::fill_n(y, 4 * size_t{node_count_}, 0.0);
  const double* v = values_.data();
  double x_dot_y = 0.0;
  for (uint32_t i = 0; i < node_count_; ++i) {
    const double* xi = x + 4 * size_t{i};
    const Lanes4 x0 = TACTA_SPLAT4(xi[0]), x1 = TACTA_SPLAT4(xi[1]), x2 = TACTA_SPLAT4(xi[2]);
    // acc_r: row r of each block times x_j, lane by lane; its lanes summed at the row's end.
    Lanes4 acc0 = TACTA_SPLAT4(0.0), acc1 = acc0, acc2 = acc0;
    for (uint32_t k = row_starts_[i]; k < row_starts_[i + 1]; ++k) {
      const double* b = v + 12 * size_t{k};
      const size_t j = 4 * size_t{columns_[k]};
      Lanes4 b0, b1, b2, xj;
      std::memcpy(&b0, b, sizeof b0);
      std::memcpy(&b1, b + 4, sizeof b1);
      std::memcpy(&b2, b + 8, sizeof b2);
      std::memcpy(&xj, x + j, sizeof xj);
      acc0 += b0 * xj;
      acc1 += b1 * xj;
      acc2 += b2 * xj;
      if (k == row_starts_[i]) continue;  // the diagonal block has no mirror
      Lanes4 yj;                          // the mirrored block (j, i) = B^T
      std::memcpy(&yj, y + j, sizeof yj);
      yj += x0 * b0 + x1 * b1 + x2 * b2;
      std::memcpy(y + j, &yj, sizeof yj);
    }
    double* yi = y + 4 * size_t{i};
    yi[0] += (acc0[0] + acc0[1]) + (acc0[2] + acc0[3]);
    yi[1] += (acc1[0] + acc1[1]) + (acc1[2] + acc1[3]);
    yi[2] += (acc2[0] + acc2[1]) + (acc2[2] + acc2[3]);
    x_dot_y += xi[0] * yi[0] + xi[1] * yi[1] + xi[2] * yi[2];
  }
  return x_dot_y;
}

void PaddedBlocks::state_fields(StateIo& io) { io.vector(values_, "padded_values"); }

}  // namespace tacta::models::sparse
