// HyperelasticModel's Newton iterations: the dynamic step (backward Euler as a minimisation)
// and the static solve with load stepping. See hyperelastic_model.hpp for the objective.
#include <algorithm>
#include <cmath>

#include "hyperelastic_model.hpp"

namespace tacta::models::hyperelastic {

namespace {
constexpr int kMaxBacktracks = 8;    // line search halvings before the step is taken anyway
constexpr double kArmijo = 1e-4;     // sufficient decrease, fraction of the linear model
constexpr double kRounding = 1e-12;  // a change of Phi this small relative to Phi is noise
double norm(const std::vector<double>& v) {
  double sum = 0.0;
  for (const double x : v) sum += x * x;
  return std::sqrt(sum);
}
}  // namespace

double HyperelasticModel::measure_at(const Objective& o, const double* x, double energy,
                                     double* residual, double& residual_norm) noexcept {
  const size_t n = residual_.size();
  const bool has_fixed = !fixed_.empty();
  for (size_t k = 0; k < n; ++k) scratch_[k] = x[k] - o.start[k];
  const double skds = o.stiffness_damping != 0.0 ? damping_product() : 0.0;  // s.Kd s
  double inertia = 0.0, mass_damping = 0.0, work = 0.0, norm2 = 0.0;
  for (size_t k = 0; k < n; ++k) {
    const double m = masses_[k / 3];
    const double d = x[k] - o.predicted[k], s = scratch_[k];
    inertia += m * d * d;
    mass_damping += m * s * s;
    work += o.loads[k] * x[k];
    // r = -grad Phi = s (f_int + f_ext) - a M (x - x~) - b M (x - x_n) - c Kd (x - x_n)
    double r = o.potential * (forces_[k] + o.loads[k]) - o.inertia * m * d - o.mass_damping * m * s;
    if (o.stiffness_damping != 0.0) r -= o.stiffness_damping * product_[k];
    residual[k] = has_fixed && fixed_[k / 3] ? 0.0 : r;
    norm2 += residual[k] * residual[k];
  }
  residual_norm = std::sqrt(norm2);
  return 0.5 * o.inertia * inertia + 0.5 * o.mass_damping * mass_damping +
         0.5 * o.stiffness_damping * skds + o.potential * (energy - work);
}

bool HyperelasticModel::newton(const Objective& o, double* x) noexcept {
  const size_t n = residual_.size();
  const bool has_fixed = !fixed_.empty();
  double first_norm = 0.0, residual_norm = 0.0, value = 0.0;
  bool converged = false;
  bool measured = false;  // the accepted line search trial left forces_, Phi and r at x
  for (int iteration = 0;; ++iteration) {
    // The residual comes first, from the line search's forces when it has just computed them;
    // the tangent is assembled only once the residual says another correction is needed.
    const bool last = iteration == o.max_iterations;
    // A lagged system: an earlier step's A, its preconditioner and Kd, for the first
    // correction, while no element's F has moved further than tangent_reuse_change from the
    // F that Kd was assembled at (the force pass measures it).
    bool lagged = iteration == 0 && o.reuse_system && system_valid_ &&
                  system_age_ < options_.tangent_reuse_steps;
    bool tangent_ready = false;
    if (!measured && (last || lagged)) {
      std::fill(forces_.begin(), forces_.end(), 0.0);
      deformation_change_ = 0.0;
      track_change_ = lagged && !last;  // may cut the pass short: only when a tangent follows
      const double energy = element_pass(x, forces_.data(), 0.0);
      track_change_ = false;
      lagged = lagged &&
               deformation_change_ <= options_.tangent_reuse_change * options_.tangent_reuse_change;
      if (last || lagged) value = measure_at(o, x, energy, residual_.data(), residual_norm);
    }
    if (!measured && !last && !lagged) {
      zero_system();
      std::fill(forces_.begin(), forces_.end(), 0.0);
      record_deformation_ = iteration == 0;
      const double energy = element_pass(x, forces_.data(), o.potential);
      record_deformation_ = false;
      tangent_ready = true;
      if (iteration == 0 && o.stiffness_damping != 0.0)  // Kd: the tangent at the first iterate
        store_damping(o.potential);
      value = measure_at(o, x, energy, residual_.data(), residual_norm);
    }
    if (iteration == 0) first_norm = residual_norm;
    if (residual_norm <= o.absolute_tolerance ||
        (iteration > 0 && residual_norm <= o.relative_tolerance * first_norm)) {
      converged = true;
      break;
    }
    if (last) break;
    ++counters_.newton_iterations;
    if (lagged) {
      ++system_age_;
      ++counters_.lagged_tangents;
    } else {
      if (!tangent_ready) {  // forces_ and Phi at x are the line search's; only K is missing
        zero_system();
        std::fill(forces_.begin(), forces_.end(), 0.0);
        element_pass(x, forces_.data(), o.potential);
      }
      finish_system(o);
      system_valid_ = o.reuse_system;
      if (iteration == 0) system_age_ = 0;  // the age of Kd, which only a first iterate sets
    }
    if (iteration == 0 && o.first_guess != nullptr)
      std::copy_n(o.first_guess, n, correction_.begin());
    else
      std::fill(correction_.begin(), correction_.end(), 0.0);
    if (!solver_->solve(matrix_, residual_.data(), correction_.data(), lagged).converged) {
      linear_solve_failed_ = true;
      system_valid_ = false;  // the next step starts from a fresh tangent
    }
    if (has_fixed)
      for (size_t k = 0; k < n; ++k)
        if (fixed_[k / 3]) correction_[k] = 0.0;
    // Backtracking on Phi along the correction: Phi(x + t d) <= Phi(x) - armijo t r.d. Near
    // the solution that decrease sinks below Phi's rounding (Phi carries f_ext . x in absolute
    // positions), so a step whose change of Phi is at rounding level passes when it halves |r|.
    double slope = 0.0;
    for (size_t k = 0; k < n; ++k) slope += residual_[k] * correction_[k];
    double t = 1.0, trial_norm = 0.0;
    for (int backtrack = 0; backtrack <= kMaxBacktracks; ++backtrack) {
      for (size_t k = 0; k < n; ++k) trial_[k] = x[k] + t * correction_[k];
      std::fill(forces_.begin(), forces_.end(), 0.0);
      const double energy = element_pass(trial_.data(), forces_.data(), 0.0);
      const double trial_value =
          measure_at(o, trial_.data(), energy, trial_residual_.data(), trial_norm);
      const bool decreased = trial_value <= value - kArmijo * t * slope;
      const bool in_rounding = std::abs(trial_value - value) <= kRounding * std::abs(value) &&
                               trial_norm <= 0.5 * residual_norm;
      if (std::isfinite(trial_value) && (decreased || in_rounding)) {
        value = trial_value;
        break;
      }
      if (backtrack == kMaxBacktracks) {  // take the shortest step anyway
        value = trial_value;
        break;
      }
      ++counters_.line_search_backtracks;
      t *= 0.5;
    }
    for (size_t k = 0; k < n; ++k) x[k] += t * correction_[k];
    residual_.swap(trial_residual_);
    residual_norm = trial_norm;
    measured = true;
  }
  return converged;
}

}  // namespace tacta::models::hyperelastic

namespace tacta::models::hyperelastic {

uint32_t HyperelasticModel::step_dynamic(tacta_body_state& state, double h) noexcept {
  const size_t n = forces_.size();
  const bool has_fixed = !fixed_.empty();
  for (size_t k = 0; k < n; ++k) {
    const bool held = has_fixed && fixed_[k / 3];
    start_[k] = state.positions[k];
    predicted_[k] = held ? start_[k] : start_[k] + h * state.velocities[k];
    loads_[k] = state.external_forces[k];
  }
  std::copy(predicted_.begin(), predicted_.end(), state.positions);
  if (h != system_step_) system_valid_ = false;  // A holds h in its weights
  system_step_ = h;
  const Objective objective{1.0,
                            h * rayleigh_mass_,
                            h * rayleigh_stiffness_,
                            h * h,
                            predicted_.data(),
                            start_.data(),
                            loads_.data(),
                            last_correction_.data(),
                            options_.newton_iterations,
                            options_.newton_tolerance,
                            0.0,
                            true};
  // Newton stopping at its iteration cap is the usual haptic-rate compromise (counted); a
  // linear solve that failed every fallback is a warning.
  if (!newton(objective, state.positions)) {
    ++counters_.unconverged_steps;
    system_valid_ = false;
  }
  const uint32_t result = linear_solve_failed_ ? TACTA_STEP_SOLVER_NOT_CONVERGED : TACTA_STEP_OK;
  for (size_t k = 0; k < n; ++k) {
    // The whole correction from the prediction: the next step's first guess (a smooth motion
    // changes it slowly).
    last_correction_[k] = state.positions[k] - predicted_[k];
    state.velocities[k] = (state.positions[k] - start_[k]) / h;
  }
  return result;
}

uint32_t HyperelasticModel::solve_static(tacta_body_state& state) noexcept {
  const size_t n = forces_.size();
  ++counters_.static_solves;
  // The load scale for the convergence test: the loads on free nodes, or (prescribed motion
  // alone) the reactions at the held ones, measured at the start.
  std::fill(forces_.begin(), forces_.end(), 0.0);
  element_pass(state.positions, forces_.data(), 0.0);
  double load_scale2 = 0.0, reaction2 = 0.0;
  for (size_t k = 0; k < n; ++k) {
    const bool held = !fixed_.empty() && fixed_[k / 3];
    (held ? reaction2 : load_scale2) +=
        held ? forces_[k] * forces_[k] : state.external_forces[k] * state.external_forces[k];
  }
  const double load_scale = std::max({std::sqrt(load_scale2), std::sqrt(reaction2), 1e-12});
  double done = 0.0, increment = 1.0 / std::max(1, options_.load_steps);
  int cuts = 0;
  bool failed = false;
  while (done < 1.0 && !failed) {
    const double target = std::min(1.0, done + increment);
    for (size_t k = 0; k < n; ++k)
      loads_[k] =
          equilibrium_loads_[k] + target * (state.external_forces[k] - equilibrium_loads_[k]);
    std::copy_n(state.positions, n, start_.begin());
    const Objective objective{0.0,
                              0.0,
                              0.0,
                              1.0,
                              start_.data(),
                              start_.data(),
                              loads_.data(),
                              nullptr,
                              options_.static_iterations,
                              0.0,
                              options_.static_tolerance * load_scale,
                              false};
    ++counters_.load_increments;
    if (newton(objective, state.positions)) {
      done = target;
      continue;
    }
    std::copy(start_.begin(), start_.end(), state.positions);  // undo, and take half the step
    ++counters_.load_cuts;
    increment *= 0.5;
    failed = ++cuts > options_.max_load_cuts;
  }
  counters_.last_static_residual = norm(residual_);
  if (failed) {
    ++counters_.unconverged_steps;
    return TACTA_STEP_SOLVER_NOT_CONVERGED;
  }
  for (size_t k = 0; k < n; ++k) {
    equilibrium_loads_[k] = state.external_forces[k];
    state.velocities[k] = 0.0;
  }
  return TACTA_STEP_OK;
}

uint32_t HyperelasticModel::step(tacta_body_state& state, double dt) noexcept {
  ++counters_.steps;
  linear_solve_failed_ = false;
  stepping_ = true;
  uint32_t result =
      options_.mode == SolveMode::kStatic ? solve_static(state) : step_dynamic(state, dt);
  stepping_ = false;
  if (inverted_) {
    result |= TACTA_STEP_INVERTED_ELEMENT;
    ++counters_.inverted_element_steps;
  }
  return result | guard_.check(state.positions, state.velocities);
}

void HyperelasticModel::state_fields(StateIo& io) {
  io.value(counters_, "newton_counters");
  io.vector(last_correction_, "last_correction");
  io.vector(equilibrium_loads_, "equilibrium_loads");
  io.value(inverted_, "inverted");
  io.value(system_valid_, "system_valid");
  io.value(system_age_, "system_age");
  io.value(system_step_, "system_step");
  io.vector(assembled_deformation_, "assembled_deformation");
  io.values(matrix_.values(), "system_matrix");
  io.values(damping_.values(), "damping_matrix");
  solver_->state_fields(io);
}

void HyperelasticModel::begin(const tacta_body_state& /*state*/, double /*dt*/) noexcept {
  std::fill(last_correction_.begin(), last_correction_.end(), 0.0);
  system_valid_ = false;
}

}  // namespace tacta::models::hyperelastic
