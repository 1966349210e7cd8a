// step()'s element pass four tets at a time: the same arithmetic as frame_of() + accumulate()
// with the polar warm start of step(), laid out as structure-of-arrays over 4 lanes so that
// every operation is a loop over the lanes the compiler turns into one vector instruction
// (AVX2 in the x86-64-v3 clone, SSE2 pairs otherwise). Gathers of node positions and scatters
// into forces and matrix blocks stay scalar. A lane whose single Newton step does not end the
// polar iteration is finished by the scalar polar_rotation(); under `svd` an inverted tet, or
// one that iteration does not finish, takes the SVD.
#include <cmath>
#include <cstring>

#include "corotational_fem.hpp"
#include "element_rotation.hpp"
#include "hot_path.hpp"
#include "lanes4.hpp"

namespace tacta::models::corotational {

namespace {
constexpr int kLanes = CorotationalFem::kBatchLanes;
constexpr int kPolarMaxIterations = 30;
constexpr double kAngleTolerance2 = 1e-24;   // rad^2, as in polar_rotation()
constexpr double kNewtonFinalStep2 = 1e-12;  // rad^2, as in polar_rotation()
constexpr int kPairA[10] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3};
constexpr int kPairB[10] = {0, 1, 2, 3, 1, 2, 3, 2, 3, 3};

using Lanes = double[kLanes];

// Rotation matrix (row-major r[3 * i + j]) of unit quaternions (w, x, y, z), per lane.
inline void quaternion_to_matrix(const Lanes& w, const Lanes& x, const Lanes& y, const Lanes& z,
                                 Lanes (&r)[9]) {
  for (int l = 0; l < kLanes; ++l) {
    r[0][l] = 1.0 - 2.0 * (y[l] * y[l] + z[l] * z[l]);
    r[1][l] = 2.0 * (x[l] * y[l] - z[l] * w[l]);
    r[2][l] = 2.0 * (x[l] * z[l] + y[l] * w[l]);
    r[3][l] = 2.0 * (x[l] * y[l] + z[l] * w[l]);
    r[4][l] = 1.0 - 2.0 * (x[l] * x[l] + z[l] * z[l]);
    r[5][l] = 2.0 * (y[l] * z[l] - x[l] * w[l]);
    r[6][l] = 2.0 * (x[l] * z[l] - y[l] * w[l]);
    r[7][l] = 2.0 * (y[l] * z[l] + x[l] * w[l]);
    r[8][l] = 1.0 - 2.0 * (x[l] * x[l] + y[l] * y[l]);
  }
}
// Rows r0..r3 of four lanes each, transposed: out[l] = (r0[l], r1[l], r2[l], r3[l]).
inline void transpose4(const sparse::Lanes4& r0, const sparse::Lanes4& r1, const sparse::Lanes4& r2,
                       const sparse::Lanes4& r3, sparse::Lanes4 (&out)[4]) {
  const sparse::Lanes4 even01 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6);
  const sparse::Lanes4 odd01 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
  const sparse::Lanes4 even23 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6);
  const sparse::Lanes4 odd23 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
  out[0] = __builtin_shufflevector(even01, even23, 0, 1, 4, 5);
  out[1] = __builtin_shufflevector(odd01, odd23, 0, 1, 4, 5);
  out[2] = __builtin_shufflevector(even01, even23, 2, 3, 6, 7);
  out[3] = __builtin_shufflevector(odd01, odd23, 2, 3, 6, 7);
}
}  // namespace

void CorotationalFem::build_batches() {
  const uint32_t batches = static_cast<uint32_t>(elements_.size()) / kLanes;
  batches_.resize(batches);
  for (uint32_t b = 0; b < batches; ++b)
    for (int l = 0; l < kLanes; ++l) {
      const Element& element = elements_[kLanes * b + l];
      for (int a = 0; a < 4; ++a)
        for (int c = 0; c < 3; ++c) batches_[b].gradients[a][c][l] = element.gradients[a][c];
      batches_[b].volume[l] = element.volume;
      for (int a = 0; a < 4; ++a) batches_[b].nodes[a][l] = element.nodes[a];
    }
}

TACTA_HOT_PATH uint32_t CorotationalFem::step_batch(uint32_t batch, const double* positions,
                                                    double scale, long& polar_iterations) noexcept {
  const ElementBatch& rest = batches_[batch];
  const uint32_t first = kLanes * batch;
  // Deformation gradient F = sum_a x_a grad_a^T, row-major.
  Lanes f[9] = {};
  for (int a = 0; a < 4; ++a) {
    Lanes x[3];
    for (int l = 0; l < kLanes; ++l)
      for (int c = 0; c < 3; ++c) x[c][l] = positions[3 * size_t{rest.nodes[a][l]} + c];
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < kLanes; ++l) f[3 * r + k][l] += x[r][l] * rest.gradients[a][k][l];
  }
  // Warm start q = turn * last (Eigen's coeffs are x, y, z, w).
  Lanes tw, tx, ty, tz, lw, lx, ly, lz, qw, qx, qy, qz;
  for (int l = 0; l < kLanes; ++l) {
    const double* turn = step_turn_[first + l].coeffs().data();
    const double* last = step_rotation_[first + l].coeffs().data();
    tx[l] = turn[0], ty[l] = turn[1], tz[l] = turn[2], tw[l] = turn[3];
    lx[l] = last[0], ly[l] = last[1], lz[l] = last[2], lw[l] = last[3];
  }
  for (int l = 0; l < kLanes; ++l) {
    qw[l] = tw[l] * lw[l] - tx[l] * lx[l] - ty[l] * ly[l] - tz[l] * lz[l];
    qx[l] = tw[l] * lx[l] + tx[l] * lw[l] + ty[l] * lz[l] - tz[l] * ly[l];
    qy[l] = tw[l] * ly[l] - tx[l] * lz[l] + ty[l] * lw[l] + tz[l] * lx[l];
    qz[l] = tw[l] * lz[l] + tx[l] * ly[l] - ty[l] * lx[l] + tz[l] * lw[l];
  }
  // One Newton step of polar_rotation() on every lane.
  Lanes rot[9];
  quaternion_to_matrix(qw, qx, qy, qz, rot);
  Lanes b[9];
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < kLanes; ++l)
        b[3 * r + k][l] = f[3 * r][l] * rot[3 * k][l] + f[3 * r + 1][l] * rot[3 * k + 1][l] +
                          f[3 * r + 2][l] * rot[3 * k + 2][l];
  Lanes wx, wy, wz;
  bool stepped[kLanes], finished[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    // g: the torque sum_i r_i x f_i, gradient of tr(R^T F) in the rotation.
    const double gx = b[7][l] - b[5][l], gy = b[2][l] - b[6][l], gz = b[3][l] - b[1][l];
    const double trace = b[0][l] + b[4][l] + b[8][l];
    const double h00 = trace - b[0][l], h11 = trace - b[4][l], h22 = trace - b[8][l];
    const double h01 = -0.5 * (b[1][l] + b[3][l]);
    const double h02 = -0.5 * (b[2][l] + b[6][l]);
    const double h12 = -0.5 * (b[5][l] + b[7][l]);
    const double c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22;
    const double c02 = h01 * h12 - h02 * h11, c11 = h00 * h22 - h02 * h02;
    const double c12 = h01 * h02 - h00 * h12, c22 = h00 * h11 - h01 * h01;
    const double determinant = h00 * c00 + h01 * c01 + h02 * c02;
    const bool converged =
        gx * gx + gy * gy + gz * gz < 4.0 * kAngleTolerance2 * (trace * trace) / 9.0;
    const bool newton = h00 > 0.0 && c22 > 0.0 && determinant > 1e-12 * h00 * h00 * h00;
    const double newton_scale = newton ? 1.0 / determinant : 0.0;
    const double safe_scale = newton ? 0.0 : 1.0 / (std::abs(trace) + 1e-9);
    const double keep = converged ? 0.0 : 1.0;
    wx[l] = keep * (newton_scale * (c00 * gx + c01 * gy + c02 * gz) + safe_scale * gx);
    wy[l] = keep * (newton_scale * (c01 * gx + c11 * gy + c12 * gz) + safe_scale * gy);
    wz[l] = keep * (newton_scale * (c02 * gx + c12 * gy + c22 * gz) + safe_scale * gz);
    stepped[l] = !converged;
    finished[l] =
        converged || (newton && wx[l] * wx[l] + wy[l] * wy[l] + wz[l] * wz[l] < kNewtonFinalStep2);
  }
  // q += (0, w/2) q, renormalised.
  for (int l = 0; l < kLanes; ++l) {
    const double hx = 0.5 * wx[l], hy = 0.5 * wy[l], hz = 0.5 * wz[l];
    const double nw = qw[l] - (hx * qx[l] + hy * qy[l] + hz * qz[l]);
    const double nx = qx[l] + hx * qw[l] + hy * qz[l] - hz * qy[l];
    const double ny = qy[l] - hx * qz[l] + hy * qw[l] + hz * qx[l];
    const double nz = qz[l] + hx * qy[l] - hy * qx[l] + hz * qw[l];
    const double inverse_norm = 1.0 / std::sqrt(nw * nw + nx * nx + ny * ny + nz * nz);
    qw[l] = nw * inverse_norm;
    qx[l] = nx * inverse_norm;
    qy[l] = ny * inverse_norm;
    qz[l] = nz * inverse_norm;
  }
  Lanes det;
  for (int l = 0; l < kLanes; ++l)
    det[l] = f[0][l] * (f[4][l] * f[8][l] - f[5][l] * f[7][l]) -
             f[1][l] * (f[3][l] * f[8][l] - f[5][l] * f[6][l]) +
             f[2][l] * (f[3][l] * f[7][l] - f[4][l] * f[6][l]);
  const bool svd = options_.rotation == RotationMethod::kSvd;
  uint32_t result = TACTA_STEP_OK;
  for (int l = 0; l < kLanes; ++l) {
    polar_iterations += stepped[l] ? 1 : 0;
    if (det[l] <= 0.0) result |= TACTA_STEP_INVERTED_ELEMENT;
    // With det F > 0 the rotation maximising tr(R^T F) is F's polar factor, U V^T, which the
    // Newton iteration finds to ~1e-12 rad: under `svd` only an inverted tet, or one the
    // iteration does not finish, takes the SVD. A lane the single step did not finish goes on
    // in the scalar iteration.
    if (!finished[l] || (svd && det[l] <= 0.0)) {
      Eigen::Quaterniond q(qw[l], qx[l], qy[l], qz[l]);
      Eigen::Matrix3d deformation;
      for (int i = 0; i < 9; ++i) deformation(i / 3, i % 3) = f[i][l];
      bool take_svd = svd && det[l] <= 0.0;
      if (!take_svd) {
        const int taken = polar_rotation(deformation, q, kPolarMaxIterations - 1);
        polar_iterations += taken;
        take_svd = svd && taken >= kPolarMaxIterations - 1;
      }
      if (take_svd) q = Eigen::Quaterniond(svd_rotation(deformation));
      qw[l] = q.w();
      qx[l] = q.x();
      qy[l] = q.y();
      qz[l] = q.z();
    }
  }
  // History: turn = q last^-1 (last is a unit quaternion: its inverse is its conjugate).
  for (int l = 0; l < kLanes; ++l) {
    tw[l] = qw[l] * lw[l] + qx[l] * lx[l] + qy[l] * ly[l] + qz[l] * lz[l];
    tx[l] = -qw[l] * lx[l] + qx[l] * lw[l] - qy[l] * lz[l] + qz[l] * ly[l];
    ty[l] = -qw[l] * ly[l] + qx[l] * lz[l] + qy[l] * lw[l] - qz[l] * lx[l];
    tz[l] = -qw[l] * lz[l] - qx[l] * ly[l] + qy[l] * lx[l] + qz[l] * lw[l];
  }
  for (int l = 0; l < kLanes; ++l) {
    double* turn = step_turn_[first + l].coeffs().data();
    double* last = step_rotation_[first + l].coeffs().data();
    turn[0] = tx[l], turn[1] = ty[l], turn[2] = tz[l], turn[3] = tw[l];
    last[0] = qx[l], last[1] = qy[l], last[2] = qz[l], last[3] = qw[l];
  }
  quaternion_to_matrix(qw, qx, qy, qz, rot);
  // Strain eps = sym(R^T F) - I, stress, world stress R sigma.
  Lanes stress[9], world[9];
  Lanes g[9];  // R^T F
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < kLanes; ++l)
        g[3 * r + k][l] =
            rot[r][l] * f[k][l] + rot[3 + r][l] * f[3 + k][l] + rot[6 + r][l] * f[6 + k][l];
  for (int l = 0; l < kLanes; ++l) {
    const double trace = g[0][l] + g[4][l] + g[8][l] - 3.0;
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k) {
        const double strain = 0.5 * (g[3 * r + k][l] + g[3 * k + r][l]) - (r == k ? 1.0 : 0.0);
        stress[3 * r + k][l] = 2.0 * mu_ * strain + (r == k ? lambda_ * trace : 0.0);
      }
  }
  for (int r = 0; r < 3; ++r)
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < kLanes; ++l)
        world[3 * r + k][l] = rot[3 * r][l] * stress[k][l] + rot[3 * r + 1][l] * stress[3 + k][l] +
                              rot[3 * r + 2][l] * stress[6 + k][l];
  // Rotated gradients c_a = R grad_a; forces f_a = -V (R sigma) grad_a.
  Lanes c[4][3];
  for (int a = 0; a < 4; ++a) {
    Lanes force[3];
    for (int r = 0; r < 3; ++r)
      for (int l = 0; l < kLanes; ++l) {
        const double g0 = rest.gradients[a][0][l], g1 = rest.gradients[a][1][l],
                     g2 = rest.gradients[a][2][l];
        c[a][r][l] = rot[3 * r][l] * g0 + rot[3 * r + 1][l] * g1 + rot[3 * r + 2][l] * g2;
        force[r][l] = -rest.volume[l] *
                      (world[3 * r][l] * g0 + world[3 * r + 1][l] * g1 + world[3 * r + 2][l] * g2);
      }
    for (int l = 0; l < kLanes; ++l) {
      double* target = &forces_[3 * size_t{rest.nodes[a][l]}];
      for (int r = 0; r < 3; ++r) target[r] += force[r][l];
    }
  }
  // K_ab = V (lambda c_a c_b^T + mu c_b c_a^T + mu (grad_a . grad_b) I), the four lanes at once.
  // An element's nodes ascend (ascending_tets): the stored block (node a, node b) is K_ab, which
  // each lane adds as two 4-wide runs and its last entry, read out of the lanes (a transpose).
  using sparse::Lanes4;
  Lanes4 cv[4][3], grad[4][3], lambda_v, mu_v;
  for (int a = 0; a < 4; ++a)
    for (int r = 0; r < 3; ++r) {
      std::memcpy(&cv[a][r], c[a][r], sizeof(Lanes4));
      std::memcpy(&grad[a][r], rest.gradients[a][r], sizeof(Lanes4));
    }
  std::memcpy(&lambda_v, rest.volume, sizeof(Lanes4));
  mu_v = lambda_v * (scale * mu_);
  lambda_v *= scale * lambda_;
  for (int p = 0; p < 10; ++p) {
    const int a = kPairA[p], bb = kPairB[p];
    Lanes4 k[9];
    for (int r = 0; r < 3; ++r)
      for (int q = 0; q < 3; ++q)
        k[3 * r + q] = lambda_v * cv[a][r] * cv[bb][q] + mu_v * cv[bb][r] * cv[a][q];
    const Lanes4 diagonal =
        mu_v * (grad[a][0] * grad[bb][0] + grad[a][1] * grad[bb][1] + grad[a][2] * grad[bb][2]);
    k[0] += diagonal;
    k[4] += diagonal;
    k[8] += diagonal;
    Lanes4 heads[4], middles[4];
    transpose4(k[0], k[1], k[2], k[3], heads);
    transpose4(k[4], k[5], k[6], k[7], middles);
    for (int l = 0; l < kLanes; ++l) {
      double* block = matrix_.block(matrix_.element_slots(first + l)[p]);
      Lanes4 head, middle;
      std::memcpy(&head, block, sizeof head);
      std::memcpy(&middle, block + 4, sizeof middle);
      head += heads[l];
      middle += middles[l];
      std::memcpy(block, &head, sizeof head);
      std::memcpy(block + 4, &middle, sizeof middle);
      block[8] += k[8][l];
    }
  }
  return result;
}

}  // namespace tacta::models::corotational
