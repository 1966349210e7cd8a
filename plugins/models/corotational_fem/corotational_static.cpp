// CorotationalFem's static solve: Newton iterations on f_int(x) + f_ext = 0 with the
// corotational stiffness R K0 R^T as tangent (it leaves out the rotation's own derivative, so
// convergence is fast but not quadratic in large rotations), a step halved when it makes the
// residual explode, and the load change since the last equilibrium applied in increments.
#include <algorithm>
#include <cmath>

#include "corotational_fem.hpp"

namespace tacta::models::corotational {

namespace {
constexpr int kMaxHalvings = 6;         // of a Newton step that makes the residual explode
constexpr double kGrowthLimit = 100.0;  // residual growth that counts as exploding
constexpr int kMaxLoadCuts = 8;         // halvings of a failed load increment
}  // namespace

double CorotationalFem::equilibrium_residual(const double* positions, bool with_matrix) noexcept {
  matrix_.set_zero();
  std::fill(forces_.begin(), forces_.end(), 0.0);
  for (uint32_t e = 0; e < elements_.size(); ++e)
    accumulate(e, frame_of(e, positions, polar_guess_[e]), with_matrix ? 1.0 : 0.0, forces_.data());
  double sum = 0.0;
  for (size_t k = 0; k < rhs_.size(); ++k) {
    rhs_[k] = !fixed_.empty() && fixed_[k / 3] ? 0.0 : forces_[k] + loads_[k];
    sum += rhs_[k] * rhs_[k];
  }
  if (with_matrix) matrix_.apply_fixed(fixed_);
  return std::sqrt(sum);
}

bool CorotationalFem::newton_to_equilibrium(double* positions, double tolerance) noexcept {
  double residual = equilibrium_residual(positions, true);
  for (int iteration = 0; iteration < options_.static_iterations; ++iteration) {
    if (residual <= tolerance) return true;
    ++static_counters_.newton_iterations;
    std::fill(delta_v_.begin(), delta_v_.end(), 0.0);  // here: the position correction, m
    last_solve_ = solver_->solve(matrix_, rhs_.data(), delta_v_.data());
    double step = 1.0;
    for (int halving = 0;; ++halving) {
      for (size_t k = 0; k < delta_v_.size(); ++k) positions[k] += step * delta_v_[k];
      // The tangent is not exact, so the residual may rise on the way to equilibrium: only a
      // step that makes it explode (or not finite) is shortened.
      const double trial = equilibrium_residual(positions, false);
      if (trial < kGrowthLimit * residual || halving == kMaxHalvings) break;
      for (size_t k = 0; k < delta_v_.size(); ++k) positions[k] -= step * delta_v_[k];
      step *= 0.5;
    }
    residual = equilibrium_residual(positions, true);
  }
  static_counters_.last_residual = residual;
  return residual <= tolerance;
}

uint32_t CorotationalFem::solve_static(tacta_body_state& state) noexcept {
  const size_t n = forces_.size();
  ++static_counters_.solves;
  // Load scale: the loads on free nodes, or (prescribed motion alone) the reactions at the
  // held ones, at the start.
  std::fill(loads_.begin(), loads_.end(), 0.0);
  (void)equilibrium_residual(state.positions, false);
  double free2 = 0.0, held2 = 0.0;
  for (size_t k = 0; k < n; ++k) {
    if (!fixed_.empty() && fixed_[k / 3])
      held2 += forces_[k] * forces_[k];
    else
      free2 += state.external_forces[k] * state.external_forces[k];
  }
  const double tolerance =
      options_.static_tolerance * std::max({std::sqrt(free2), std::sqrt(held2), 1e-12});
  double done = 0.0, increment = 1.0 / std::max(1, options_.load_steps);
  int cuts = 0;
  while (done < 1.0) {
    const double target = std::min(1.0, done + increment);
    for (size_t k = 0; k < n; ++k)
      loads_[k] =
          equilibrium_loads_[k] + target * (state.external_forces[k] - equilibrium_loads_[k]);
    std::copy_n(state.positions, n, static_start_.begin());
    ++static_counters_.load_increments;
    if (newton_to_equilibrium(state.positions, tolerance)) {
      done = target;
      continue;
    }
    std::copy(static_start_.begin(), static_start_.end(), state.positions);
    ++static_counters_.load_cuts;
    increment *= 0.5;
    if (++cuts > kMaxLoadCuts) {
      ++static_counters_.unconverged;
      return TACTA_STEP_SOLVER_NOT_CONVERGED | guard_.check(state.positions, state.velocities);
    }
  }
  static_counters_.last_residual = equilibrium_residual(state.positions, false);
  for (size_t k = 0; k < n; ++k) {
    equilibrium_loads_[k] = state.external_forces[k];
    state.velocities[k] = 0.0;
  }
  return guard_.check(state.positions, state.velocities);
}

}  // namespace tacta::models::corotational
