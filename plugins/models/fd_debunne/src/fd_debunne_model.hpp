// Debunne et al.'s explicit finite-difference model (paper section 3, eqs. 7, 13, 17).
//
//   rho a_i = mu Lap(d)_i + (lambda + mu) grad(div d)_i + external,   d = x - x_rest
//   Lap(d)_i      = s * 2/(sum_j L_ij) * sum_j (d_j - d_i) / L_ij                      (13)
//   graddiv(d)_i  = s * 2/(sum_j L_ij) * sum_j ((d_j - d_i).u_ij) u_ij / L_ij           (17)
//
// over the mesh edge graph, on the rest geometry (L_ij rest lengths, u_ij rest directions).
// The nodal force is the force per unit volume times the node's lumped volume m_i / rho.
// s is the operator scale: 1 as printed in the paper, or the mesh dimension. On a Cartesian edge
// graph the printed operators are exactly 1/dimension of the continuous ones (the 2/sum(L)
// average spreads one axis' second difference over all axes), so s = dimension gives the right
// wave speeds there (measured by the wave-speed tests; see docs/VALIDATION.md).
//
// The paper's form weights the pair (i, j) by 2 V_i / (S_i L_ij) on node i and by
// 2 V_j / (S_j L_ij) on node j: the pair forces differ, and linear momentum is not conserved on
// an irregular mesh. The symmetric variant uses the mean of the two weights on both sides:
// equal and opposite pair forces, a symmetric stiffness and an exact elastic energy.
#pragma once

#include <cstdint>
#include <vector>

#include "tacta/model_api.h"
#include "tacta/models/divergence_guard.hpp"

namespace tacta::models {

struct FdDebunneOptions {
  enum class Integrator { kSymplecticEuler = 0, kExplicitEuler = 1 };
  enum class OperatorScale { kPaper = 0, kDimension = 1 };
  Integrator integrator = Integrator::kSymplecticEuler;
  double damping = 0.0;  // N s/m: force -damping * v on every node
  bool symmetric = false;
  OperatorScale operator_scale = OperatorScale::kDimension;
  double divergence_stretch = DivergenceGuard::kDefaultStretchLimit;  // edge length ratio
};

class FdDebunneModel {
 public:
  FdDebunneModel(const tacta_model_setup& setup, const FdDebunneOptions& options);

  uint32_t step(tacta_body_state& state, double dt) noexcept;
  // Linear model: F = -K d. For the symmetric variant this is the exact potential 1/2 d.K d;
  // for the paper's form it is the same quadratic form -1/2 d.F(d), which is not conserved.
  double elastic_energy(const double* positions) noexcept;
  void internal_forces(const double* positions, double* forces) const noexcept;

  const FdDebunneOptions& options() const { return options_; }
  void set_damping(double damping) { options_.damping = damping; }
  double operator_scale() const { return scale_; }

 private:
  FdDebunneOptions options_;
  uint32_t node_count_ = 0;
  std::vector<double> rest_;  // 3 per node, m
  std::vector<double> mass_;  // kg
  std::vector<uint8_t> fixed_;
  std::vector<uint32_t> offset_;  // compressed rows of neighbours
  std::vector<uint32_t> neighbour_;
  std::vector<double> weight_;          // per (i, j) entry: s * 2 V_i / (S_i L_ij), m (N/m per Pa)
  std::vector<double> direction_;       // per (i, j) entry: rest unit vector u_ij, 3 each
  double mu_ = 0, lambda_plus_mu_ = 0;  // Pa
  double scale_ = 1;
  std::vector<double> force_;  // scratch, 3 per node, N
  DivergenceGuard guard_;
};

}  // namespace tacta::models
