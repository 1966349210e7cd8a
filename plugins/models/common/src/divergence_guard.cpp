#include "tacta/models/divergence_guard.hpp"

#include <cmath>
#include <stdexcept>

namespace tacta::models {

DivergenceGuard::DivergenceGuard(const tacta_mesh_view& mesh, double stretch_limit)
    : node_count_(mesh.node_count),
      edges_(mesh.edges, mesh.edges + 2 * static_cast<size_t>(mesh.edge_count)),
      rest_length_sq_(mesh.edge_count),
      stretch_limit_(stretch_limit) {
  if (!(stretch_limit > 1.0)) throw std::invalid_argument("divergence stretch limit must be > 1");
  for (uint32_t e = 0; e < mesh.edge_count; ++e) {
    const double* a = mesh.rest_positions + 3 * static_cast<size_t>(edges_[2 * e]);
    const double* b = mesh.rest_positions + 3 * static_cast<size_t>(edges_[2 * e + 1]);
    rest_length_sq_[e] = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                         (a[2] - b[2]) * (a[2] - b[2]);
  }
}

uint32_t DivergenceGuard::check(const double* positions, const double* velocities) const noexcept {
  double sum = 0.0;  // one NaN or infinity anywhere makes the sum non-finite
  for (size_t i = 0; i < 3 * static_cast<size_t>(node_count_); ++i)
    sum += positions[i] * 0.0 + (velocities ? velocities[i] * 0.0 : 0.0);
  if (!std::isfinite(sum)) return TACTA_STEP_NOT_FINITE;
  const double limit_sq = stretch_limit_ * stretch_limit_;
  for (size_t e = 0; e < rest_length_sq_.size(); ++e) {
    const double* a = positions + 3 * static_cast<size_t>(edges_[2 * e]);
    const double* b = positions + 3 * static_cast<size_t>(edges_[2 * e + 1]);
    const double length_sq = (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                             (a[2] - b[2]) * (a[2] - b[2]);
    if (length_sq > limit_sq * rest_length_sq_[e] || length_sq * limit_sq < rest_length_sq_[e])
      return TACTA_STEP_DIVERGED;
  }
  return TACTA_STEP_OK;
}

}  // namespace tacta::models
