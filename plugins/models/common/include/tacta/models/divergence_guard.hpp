// Divergence check for the 1 kHz path: no allocation, one pass over nodes and edges.
//   TACTA_STEP_NOT_FINITE: a position or velocity is NaN or infinite.
//   TACTA_STEP_DIVERGED:   some edge is longer than stretch_limit times its rest length, or
//                          shorter than its rest length divided by stretch_limit. Edge ratios
//                          are blind to rigid motion (a falling or drifting body is not a
//                          fault) and catch the growth of an unstable explicit scheme early.
#pragma once

#include <cstdint>
#include <vector>

#include "tacta/model_api.h"

namespace tacta::models {

class DivergenceGuard {
 public:
  static constexpr double kDefaultStretchLimit = 10.0;  // dimensionless length ratio

  DivergenceGuard() = default;
  // Keeps a copy of the edge list and rest lengths (allocates here, never in check()).
  DivergenceGuard(const tacta_mesh_view& mesh, double stretch_limit = kDefaultStretchLimit);

  // Returns TACTA_STEP_OK or a mix of TACTA_STEP_NOT_FINITE / TACTA_STEP_DIVERGED.
  uint32_t check(const double* positions, const double* velocities) const noexcept;

  double stretch_limit() const { return stretch_limit_; }

 private:
  uint32_t node_count_ = 0;
  std::vector<uint32_t> edges_;         // 2 per edge
  std::vector<double> rest_length_sq_;  // m^2, 1 per edge
  double stretch_limit_ = kDefaultStretchLimit;
};

}  // namespace tacta::models
