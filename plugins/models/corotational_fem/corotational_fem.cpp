#include "corotational_fem.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "element_rotation.hpp"
#include "hot_path.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::corotational {

namespace {
using tacta::models::node_position;
using tacta::models::Vec3;
constexpr int kPolarMaxIterations = 30;  // warm-started: usually 1 to 3 are used
constexpr int kPairA[10] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3};
constexpr int kPairB[10] = {0, 1, 2, 3, 1, 2, 3, 2, 3, 3};

Vec3 node(const double* positions, uint32_t index) { return node_position(positions, index); }

// Each tet's nodes in ascending order: every node pair (a < b) then stores its block as K_ab,
// never transposed, so the element pass scatters without a branch per lane and pair.
std::vector<uint32_t> ascending_tets(const tacta_mesh_view& mesh) {
  std::vector<uint32_t> tets(mesh.tets, mesh.tets + 4 * size_t{mesh.tet_count});
  for (size_t e = 0; e < tets.size(); e += 4)
    std::sort(tets.begin() + static_cast<std::ptrdiff_t>(e),
              tets.begin() + static_cast<std::ptrdiff_t>(e + 4));
  return tets;
}
}  // namespace

CorotationalFem::CorotationalFem(const tacta_mesh_view& mesh, const tacta_material& material,
                                 std::span<const double> masses, std::span<const uint8_t> fixed,
                                 const Options& options)
    : node_count_(mesh.node_count),
      lambda_(material.lame_lambda),
      mu_(material.lame_mu),
      alpha_(material.rayleigh_mass),
      beta_(material.rayleigh_stiffness),
      rest_(mesh.rest_positions, mesh.rest_positions + 3 * static_cast<size_t>(mesh.node_count)),
      masses_(masses.begin(), masses.end()),
      fixed_(fixed.begin(), fixed.end()),
      options_(options),
      guard_(mesh),
      matrix_(mesh.node_count, ascending_tets(mesh)) {
  if (mesh.tet_count == 0)
    throw std::invalid_argument("corotational_fem needs a tetrahedral mesh (the mesh has no tets)");
  if (masses_.size() != node_count_)
    throw std::invalid_argument("corotational_fem: expected one mass per node");
  if (!(mu_ > 0.0) || !(lambda_ + 2.0 * mu_ / 3.0 > 0.0))
    throw std::invalid_argument(
        "corotational_fem: material needs lame_mu > 0 and a positive bulk "
        "modulus (got lambda " +
        std::to_string(lambda_) + " Pa, mu " + std::to_string(mu_) + " Pa)");
  check_free_node_masses("corotational_fem", masses_, fixed_);
  elements_.resize(mesh.tet_count);
  for (uint32_t e = 0; e < mesh.tet_count; ++e) {
    Element& element = elements_[e];
    const TetRest rest =
        checked_tet_rest("corotational_fem", rest_.data(), node_count_, mesh.tets, e);
    int order[4] = {0, 1, 2, 3};  // each node keeps its own gradient (as ascending_tets)
    std::sort(order, order + 4, [&](int a, int b) { return rest.nodes[a] < rest.nodes[b]; });
    for (int a = 0; a < 4; ++a) {
      element.nodes[a] = rest.nodes[order[a]];
      std::copy_n(rest.gradients[order[a]], 3, element.gradients[a]);
    }
    element.volume = rest.volume;
    for (int p = 0; p < 10; ++p) {
      const double* ga = element.gradients[kPairA[p]];
      const double* gb = element.gradients[kPairB[p]];
      element.gradient_dots[p] = ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2];
    }
  }
  polar_guess_.assign(elements_.size(), Eigen::Quaterniond::Identity());
  step_rotation_ = polar_guess_;
  step_turn_ = polar_guess_;
  build_batches();
  tile_batches();
  const size_t n = 3 * static_cast<size_t>(node_count_);
  forces_.assign(n, 0.0);
  stiffness_velocity_.assign(n, 0.0);
  rhs_.assign(n, 0.0);
  delta_v_.assign(n, 0.0);
  previous_delta_v_.assign(n, 0.0);
  older_delta_v_.assign(n, 0.0);
  guess_curvature_.assign(n, 0.0);
  weights_.assign(node_count_, 0.0);
  if (options_.static_solve) {
    if (std::find(fixed_.begin(), fixed_.end(), uint8_t{1}) == fixed_.end())
      throw std::invalid_argument(
          "corotational_fem: solve: static needs fixed nodes (a free "
          "body has no equilibrium under a net load)");
    loads_.assign(n, 0.0);
    equilibrium_loads_.assign(n, 0.0);
    static_start_.assign(n, 0.0);
  }
  solver_ = std::make_unique<SafeSolver>(
      matrix_, sparse::SolverOptions{
                   options_.solver, options_.preconditioner, options_.max_iterations,
                   options_.tolerance, options_.refactor_interval, options_.fallback,
                   options_.restart_factor, options_.threaded_solve ? options_.host : nullptr});
  rows_ = sparse::RowTeam(options_.threaded_solve ? options_.host : nullptr, node_count_,
                          kMinThreadedNodes);
  matrix_.apply_fixed(fixed_);  // builds the list of blocks to clear, while allocation is allowed
}

CorotationalFem::~CorotationalFem() = default;

void CorotationalFem::set_solver_limits(int max_iterations, double tolerance,
                                        int refactor_interval) {
  options_.max_iterations = max_iterations;
  options_.tolerance = tolerance;
  options_.refactor_interval = refactor_interval;
  solver_->set_limits(max_iterations, tolerance, refactor_interval);
}

TACTA_HOT_PATH CorotationalFem::ElementFrame CorotationalFem::frame_of(
    uint32_t e, const double* positions, Eigen::Quaterniond& guess) noexcept {
  const Element& element = elements_[e];
  Eigen::Matrix3d deformation = Eigen::Matrix3d::Zero();  // F = sum_a x_a grad_a^T
  for (int a = 0; a < 4; ++a) {
    const Eigen::Vector3d x = node(positions, element.nodes[a]);
    const Eigen::Map<const Eigen::Vector3d> g(element.gradients[a]);
    deformation.noalias() += x * g.transpose();
  }
  ElementFrame frame;
  if (options_.rotation == RotationMethod::kPolar) {
    polar_iterations_ += polar_rotation(deformation, guess, kPolarMaxIterations);
    frame.rotation = guess.toRotationMatrix();
  } else {
    frame.rotation = svd_rotation(deformation);
  }
  frame.inverted = deformation.determinant() <= 0.0;
  const Eigen::Matrix3d gradient =
      frame.rotation.transpose() * deformation - Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d strain = 0.5 * (gradient + gradient.transpose());
  frame.stress = 2.0 * mu_ * strain;
  frame.stress.diagonal().array() += lambda_ * strain.trace();
  for (int a = 0; a < 4; ++a)
    frame.rotated_gradients[a] =
        frame.rotation * Eigen::Map<const Eigen::Vector3d>(element.gradients[a]);
  return frame;
}

TACTA_HOT_PATH void CorotationalFem::accumulate(uint32_t e, const ElementFrame& frame, double scale,
                                                double* forces) noexcept {
  const Element& element = elements_[e];
  const double volume = element.volume;
  const Eigen::Matrix3d world_stress = frame.rotation * frame.stress;  // R sigma
  for (int a = 0; a < 4; ++a) {
    const Eigen::Vector3d f =
        -volume * (world_stress * Eigen::Map<const Eigen::Vector3d>(element.gradients[a]));
    for (int c = 0; c < 3; ++c) forces[3 * element.nodes[a] + c] += f[c];
  }
  const Eigen::Vector3d* c = frame.rotated_gradients;
  // K_ab = V (lambda c_a c_b^T + mu c_b c_a^T + mu (grad_a . grad_b) I); an element's nodes
  // ascend (ascending_tets), so the stored block (lower node, higher node) is K_ab.
  const double lambda_v = scale * volume * lambda_;
  const double mu_v = scale * volume * mu_;
  const uint32_t* slots = matrix_.element_slots(e);
  for (int p = 0; p < 10; ++p) {
    const int a = kPairA[p], b = kPairB[p];
    const double* ca = c[a].data();
    const double* cb = c[b].data();
    const double diagonal = mu_v * element.gradient_dots[p];
    double* block = matrix_.block(slots[p]);
    for (int r = 0; r < 3; ++r)
      for (int k = 0; k < 3; ++k)
        block[3 * r + k] += lambda_v * ca[r] * cb[k] + mu_v * cb[r] * ca[k];
    block[0] += diagonal;
    block[4] += diagonal;
    block[8] += diagonal;
  }
}

uint32_t CorotationalFem::step(tacta_body_state& state, double dt) noexcept {
  if (options_.static_solve) return solve_static(state);
  const size_t n = 3 * static_cast<size_t>(node_count_);
  const double h = dt;
  uint32_t result = TACTA_STEP_OK;
  polar_iterations_ = 0;
  const bool threaded = rows_.threaded();  // one path for the whole step (the solve's too)
  if (threaded) {
    rows_.run([&](uint32_t, uint32_t begin, uint32_t end) {
      matrix_.zero_rows(begin, end);
      std::fill(forces_.begin() + 3 * std::ptrdiff_t{begin},
                forces_.begin() + 3 * std::ptrdiff_t{end}, 0.0);
    });
  } else {
    matrix_.set_zero();
    std::fill(forces_.begin(), forces_.end(), 0.0);
  }
  const double stiffness_scale = h * beta_ + h * h;
  uint32_t e = 0;
  if (options_.batch_elements) {
    result |= batched_pass(state.positions, stiffness_scale);
    e = static_cast<uint32_t>(batches_.size()) * kBatchLanes;
  }
  for (; e < elements_.size(); ++e) {
    // Warm start extrapolated at constant angular velocity, R_n (R_n-1^T R_n): one Newton
    // step then usually suffices where the last rotation alone needed two.
    Eigen::Quaterniond rotation = step_turn_[e] * step_rotation_[e];
    const ElementFrame frame = frame_of(e, state.positions, rotation);
    step_turn_[e] = rotation * step_rotation_[e].conjugate();
    step_rotation_[e] = rotation;
    if (frame.inverted) result |= TACTA_STEP_INVERTED_ELEMENT;
    accumulate(e, frame, stiffness_scale, forces_.data());
  }
  double force2 = 0.0;
  if (threaded) {
    force2 = finish_system_threaded(state, h);
  } else {
    // The matrix holds h (beta + h) K now: its product with v is the rhs's stiffness and
    // damping term, one pass over the blocks instead of a K_e v per element.
    matrix_.multiply(state.velocities, stiffness_velocity_.data());
    matrix_.add_to_diagonal(masses_, 1.0 + h * alpha_);
    matrix_.apply_fixed(fixed_);
    force2 = rhs_rows(state, h, 0, node_count_);
    if (solver_->iterative()) extrapolate_guess(0, n);
  }
  const double floor = options_.force_scaled_tolerance ? h * std::sqrt(force2) : 0.0;
  last_solve_ = solver_->solve(matrix_, rhs_.data(), delta_v_.data(), false, floor);
  if (!last_solve_.converged) result |= TACTA_STEP_SOLVER_NOT_CONVERGED;
  if (threaded) {
    advance_threaded(state, h);
  } else {
    if (solver_->iterative() && options_.adaptive_guess) {
      double linear = 0.0, quadratic = 0.0;
      score_guess(0, n, linear, quadratic);
      quadratic_guess_ = quadratic < linear;
    }
    for (uint32_t i = 0; i < node_count_; ++i) {
      const bool held = !fixed_.empty() && fixed_[i];
      for (size_t k = 3 * size_t{i}; k < 3 * size_t{i} + 3; ++k) {
        double& v = state.velocities[k];
        v = held ? 0.0 : v + delta_v_[k];
        state.positions[k] += h * v;
      }
    }
  }
  result |= guard_.check(state.positions, state.velocities);
  return result;
}

double CorotationalFem::rhs_rows(const tacta_body_state& state, double h, uint32_t begin,
                                 uint32_t end) noexcept {
  double force2 = 0.0;
  for (uint32_t i = begin; i < end; ++i) {
    const bool held = !fixed_.empty() && fixed_[i];
    const double m = masses_[i];
    for (size_t k = 3 * size_t{i}; k < 3 * size_t{i} + 3; ++k) {
      const double f = forces_[k], f_ext = state.external_forces[k];
      rhs_[k] =
          held ? 0.0 : h * (f + f_ext - alpha_ * m * state.velocities[k]) - stiffness_velocity_[k];
      if (!held) force2 += f * f + f_ext * f_ext;
    }
  }
  return force2;
}

// CG starts from dv extrapolated over the last steps (a smooth motion changes its velocity
// increment slowly): a smaller first residual, fewer iterations. Linear over two steps, or
// quadratic over three, whichever missed this step's dv by less on the last step: the quadratic
// one follows a pressing hand closely (the liver demo: 14 CG iterations a step down to 8) but
// amplifies the solves' own rounding, which on a lightly loaded beam costs more than it saves.
// The solver drops the guess when it is worse than zero.
void CorotationalFem::extrapolate_guess(size_t begin, size_t end) noexcept {
  for (size_t k = begin; k < end; ++k) {
    const double last = delta_v_[k], before = previous_delta_v_[k];
    const double curvature = last - 2.0 * before + older_delta_v_[k];
    delta_v_[k] = 2.0 * last - before;
    if (quadratic_guess_) delta_v_[k] += curvature;
    guess_curvature_[k] = curvature;
    older_delta_v_[k] = before;
    previous_delta_v_[k] = last;
  }
}

void CorotationalFem::score_guess(size_t begin, size_t end, double& linear,
                                  double& quadratic) const noexcept {
  for (size_t k = begin; k < end; ++k) {
    const double miss = delta_v_[k] - (2.0 * previous_delta_v_[k] - older_delta_v_[k]);
    linear += miss * miss;
    quadratic += (miss - guess_curvature_[k]) * (miss - guess_curvature_[k]);
  }
}

void CorotationalFem::state_fields(StateIo& io) {
  io.vector(polar_guess_, "polar_guess");
  io.vector(step_rotation_, "step_rotation");
  io.vector(step_turn_, "step_turn");
  io.vector(delta_v_, "delta_v");
  io.vector(previous_delta_v_, "previous_delta_v");
  io.vector(older_delta_v_, "older_delta_v");
  io.value(quadratic_guess_, "quadratic_guess");
  io.vector(equilibrium_loads_, "equilibrium_loads");
  io.value(static_counters_, "static_counters");
  io.value(last_solve_, "last_solve");
  solver_->state_fields(io);
}

void CorotationalFem::begin(const tacta_body_state& state, double /*dt*/) noexcept {
  std::fill(delta_v_.begin(), delta_v_.end(), 0.0);
  std::fill(previous_delta_v_.begin(), previous_delta_v_.end(), 0.0);
  std::fill(older_delta_v_.begin(), older_delta_v_.end(), 0.0);
  quadratic_guess_ = false;
  std::fill(polar_guess_.begin(), polar_guess_.end(), Eigen::Quaterniond::Identity());
  // Converge the warm-start rotations now, so the first step is not slower than the others.
  for (uint32_t e = 0; e < elements_.size(); ++e)
    (void)frame_of(e, state.positions, polar_guess_[e]);
  step_rotation_ = polar_guess_;
  std::fill(step_turn_.begin(), step_turn_.end(), Eigen::Quaterniond::Identity());
}

double CorotationalFem::elastic_energy(const double* positions) noexcept {
  double energy = 0.0;
  for (uint32_t e = 0; e < elements_.size(); ++e) {
    const ElementFrame frame = frame_of(e, positions, polar_guess_[e]);
    // W = V (mu eps:eps + lambda/2 tr(eps)^2) = V/2 sigma:eps, eps recovered from sigma.
    Eigen::Matrix3d strain = frame.stress;
    const double trace = frame.stress.trace() / (3.0 * lambda_ + 2.0 * mu_);  // tr(eps)
    strain.diagonal().array() -= lambda_ * trace;
    strain /= 2.0 * mu_;
    energy += 0.5 * elements_[e].volume * (frame.stress.cwiseProduct(strain)).sum();
  }
  return energy;
}

void CorotationalFem::internal_forces(const double* positions, double* forces) noexcept {
  std::fill_n(forces, 3 * static_cast<size_t>(node_count_), 0.0);
  matrix_.set_zero();
  for (uint32_t e = 0; e < elements_.size(); ++e)
    accumulate(e, frame_of(e, positions, polar_guess_[e]), 0.0, forces);
}

const BlockSparseMatrix& CorotationalFem::assemble_stiffness(const double* positions) noexcept {
  matrix_.set_zero();
  std::fill(forces_.begin(), forces_.end(), 0.0);
  for (uint32_t e = 0; e < elements_.size(); ++e)
    accumulate(e, frame_of(e, positions, polar_guess_[e]), 1.0, forces_.data());
  return matrix_;
}

void CorotationalFem::node_stress(const double* positions, double* von_mises) noexcept {
  std::fill_n(von_mises, node_count_, 0.0);
  std::fill(weights_.begin(), weights_.end(), 0.0);
  for (uint32_t e = 0; e < elements_.size(); ++e) {
    const Eigen::Matrix3d s = frame_of(e, positions, polar_guess_[e]).stress;
    const double vm = std::sqrt(0.5 * ((s(0, 0) - s(1, 1)) * (s(0, 0) - s(1, 1)) +
                                       (s(1, 1) - s(2, 2)) * (s(1, 1) - s(2, 2)) +
                                       (s(2, 2) - s(0, 0)) * (s(2, 2) - s(0, 0))) +
                                3.0 * (s(0, 1) * s(0, 1) + s(1, 2) * s(1, 2) + s(0, 2) * s(0, 2)));
    for (uint32_t a : elements_[e].nodes) {  // volume-weighted average over adjacent elements
      von_mises[a] += elements_[e].volume * vm;
      weights_[a] += elements_[e].volume;
    }
  }
  for (uint32_t i = 0; i < node_count_; ++i)
    if (weights_[i] > 0.0) von_mises[i] /= weights_[i];
}

}  // namespace tacta::models::corotational
