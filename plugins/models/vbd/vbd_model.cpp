#include "vbd_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "element_energy.hpp"
#include "element_rotation.hpp"  // corotational_fem's warm-started polar rotation
#include "hot_path.hpp"          // the sweep built for AVX2 + FMA too, picked at load
#include "tacta/models/greedy_colouring.hpp"

namespace tacta::models::vbd {

namespace {
// Work per chunk a worker takes: a vertex costs one pass over its ~20 incident tets, a rotation
// one warm-started polar iteration; a chunk of tens of microseconds amortises the hand-over.
constexpr uint32_t kVertexGrain = 32;
constexpr uint32_t kTetGrain = 256;
constexpr uint32_t kNodeGrain = 1024;  // plain per-node arithmetic (Chebyshev)
// Warm-started from the last step the polar iteration needs 1-2 Newton steps; from identity
// (begin, queries on an unseen shape) up to ~10.
constexpr int kPolarIterations = 30;
// A vertex block whose determinant is below this fraction of (trace / 3)^3 is singular to
// rounding: its update is skipped. M / h^2 keeps every free vertex's block far above it.
constexpr double kSingularRatio = 1e-12;

Eigen::Vector3d vec_at(const double* a, uint32_t i) { return node_position(a, i); }
}  // namespace

VbdModel::VbdModel(const tacta_mesh_view& mesh, const tacta_material& material,
                   std::span<const double> masses, std::span<const uint8_t> fixed,
                   const Options& options)
    : node_count_(mesh.node_count),
      lambda_(material.lame_lambda),
      mu_(material.lame_mu),
      alpha_(material.rayleigh_mass),
      beta_(material.rayleigh_stiffness),
      options_(options),
      masses_(masses.begin(), masses.end()),
      guard_(mesh) {
  if (mesh.dimension != 3 || mesh.tet_count == 0)
    throw std::invalid_argument("vbd: needs a tetrahedral volume mesh (" +
                                std::to_string(mesh.tet_count) + " tets, dimension " +
                                std::to_string(mesh.dimension) + ")");
  if (masses.size() != node_count_)
    throw std::invalid_argument("vbd: " + std::to_string(masses.size()) + " masses for " +
                                std::to_string(node_count_) + " nodes");
  check_free_node_masses("vbd", masses, fixed);
  if (!(mu_ > 0.0) || !(lambda_ >= 0.0))
    throw std::invalid_argument("vbd: needs mu > 0 and lambda >= 0 (got mu " + std::to_string(mu_) +
                                " Pa, lambda " + std::to_string(lambda_) + " Pa)");
  fixed_.assign(node_count_, 0);
  std::copy(fixed.begin(), fixed.end(), fixed_.begin());
  tets_.reserve(mesh.tet_count);
  for (uint32_t e = 0; e < mesh.tet_count; ++e)
    tets_.push_back(checked_tet_rest("vbd", mesh.rest_positions, node_count_, mesh.tets, e));
  build_incidence_and_colours(fixed_);

  const size_t n3 = 3 * size_t{node_count_};
  start_.assign(n3, 0.0);
  inertia_target_.assign(n3, 0.0);
  start_force_.assign(n3, 0.0);
  previous_velocity_.assign(n3, 0.0);
  chebyshev_prev_.assign(n3, 0.0);
  chebyshev_prev2_.assign(n3, 0.0);
  elastic_hessian_.assign(node_count_, Eigen::Matrix3d::Zero());
  step_rotation_.assign(tets_.size(), Eigen::Quaterniond::Identity());
  query_rotation_ = step_rotation_;
  frames_.assign(tets_.size(), TetFrame{});
  const tacta_host_services* host = options_.host;
  tallies_.assign(host != nullptr && host->worker_count > 1 ? host->worker_count : 1u,
                  WorkerTally{});
}

void VbdModel::build_incidence_and_colours(std::span<const uint8_t> fixed) {
  const uint32_t n = node_count_;
  incidence_start_.assign(size_t{n} + 1, 0);
  for (const TetRest& t : tets_)
    for (uint32_t node : t.nodes) ++incidence_start_[size_t{node} + 1];
  for (uint32_t i = 0; i < n; ++i) incidence_start_[i + 1] += incidence_start_[i];
  incidence_.resize(incidence_start_[n]);
  std::vector<uint32_t> cursor(incidence_start_.begin(), incidence_start_.end() - 1);
  for (uint32_t e = 0; e < tets_.size(); ++e)
    for (uint32_t c = 0; c < 4; ++c) {
      const TetRest& t = tets_[e];
      incidence_[cursor[t.nodes[c]]++] = {
          {t.gradients[c][0], t.gradients[c][1], t.gradients[c][2]}, t.volume, e, c};
    }

  // Greedy colouring in node order: the smallest colour no free tet-neighbour holds yet. Fixed
  // vertices never move, so they neither need a colour nor constrain one.
  ColourGroups groups = greedy_colouring(
      n,
      [&](uint32_t i, auto&& visit) {
        for (uint32_t k = incidence_start_[i]; k < incidence_start_[i + 1]; ++k)
          for (uint32_t j : tets_[incidence_[k].tet].nodes) visit(j);
      },
      [&](uint32_t i) { return fixed[i] != 0; });
  colour_start_ = std::move(groups.starts);
  colour_vertices_ = std::move(groups.members);
}

template <class Body>
void VbdModel::for_each(uint32_t count, uint32_t grain, Body&& body) noexcept {
  const tacta_host_services* host = options_.host;
  if (host == nullptr || host->worker_count < 2 || host->parallel_for == nullptr ||
      count < 2 * grain) {
    for (uint32_t k = 0; k < count; ++k) body(k, 0u);
    return;
  }
  using B = std::remove_reference_t<Body>;
  const auto chunk = [](void* user, uint32_t begin, uint32_t end, uint32_t worker) {
    B& b = *static_cast<B*>(user);
    for (uint32_t k = begin; k < end; ++k) b(k, worker);
  };
  host->parallel_for(host->jobs, count, grain, chunk, &body);
}

Eigen::Matrix3d VbdModel::deformation(uint32_t tet, const double* positions) const noexcept {
  return tet_deformation(tets_[tet], positions);
}

TACTA_HOT_PATH void VbdModel::refresh_deformation(uint32_t e, const double* positions,
                                                  double blend) noexcept {
  // F at p = x + blend (x - x_t): the edge vectors from node 0 times the rest gradients,
  // F(r, c) = sum_a edge_a[r] grad N_a[c]; corotational: R^T F.
  const TetRest& t = tets_[e];
  const double* start = start_.data();
  const double* p0 = positions + 3 * size_t{t.nodes[0]};
  const double* s0 = start + 3 * size_t{t.nodes[0]};
  double edge[3][3];
  for (int a = 0; a < 3; ++a) {
    const double* pa = positions + 3 * size_t{t.nodes[a + 1]};
    const double* sa = start + 3 * size_t{t.nodes[a + 1]};
    for (int r = 0; r < 3; ++r) {
      const double d = pa[r] - p0[r];
      edge[a][r] = d + blend * (d - (sa[r] - s0[r]));
    }
  }
  Eigen::Matrix3d f;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      f(r, c) = edge[0][r] * t.gradients[1][c] + edge[1][r] * t.gradients[2][c] +
                edge[2][r] * t.gradients[3][c];
  TetFrame& frame = frames_[e];
  if (options_.energy == Energy::kCorotational)
    frame.deformation.noalias() = frame.rotation.transpose() * f;
  else
    frame.deformation = f;
}

void VbdModel::refresh_deformations(const double* positions, double blend) noexcept {
  for_each(static_cast<uint32_t>(tets_.size()), kTetGrain,
           [&](uint32_t e, uint32_t) { refresh_deformation(e, positions, blend); });
}

TACTA_HOT_PATH VbdModel::VertexBlock VbdModel::vertex_block(uint32_t i,
                                                            bool with_hessian) const noexcept {
  VertexBlock out;
  const Lame lame{lambda_, mu_};
  const bool corotational = options_.energy == Energy::kCorotational;
  for (uint32_t k = incidence_start_[i]; k < incidence_start_[i + 1]; ++k) {
    const Incidence& inc = incidence_[k];
    const Eigen::Vector3d g(inc.gradient[0], inc.gradient[1], inc.gradient[2]);
    const TetFrame& frame = frames_[inc.tet];
    if (corotational) {
      out.force +=
          corotational_corner_force(g, inc.volume, frame.deformation, frame.rotation, lame);
      if (with_hessian)
        out.hessian += corotational_corner_hessian(g, inc.volume, frame.rotation, lame);
    } else {
      Eigen::Vector3d force;
      Eigen::Matrix3d hessian;
      neo_hookean_corner(g, inc.volume, frame.deformation, lame, kMinVolumeRatio, force,
                         with_hessian ? &hessian : nullptr);
      out.force += force;
      if (with_hessian) out.hessian += hessian;
    }
  }
  return out;
}

TACTA_HOT_PATH void VbdModel::update_vertex(uint32_t i, double* positions, uint32_t worker,
                                            bool first_iteration) noexcept {
  const double h = h_, m = masses_[i];
  const double inertia = m / (h * h);               // N/m: M / h^2
  const double mass_damping = alpha_ * m / h;       // N/m: alpha M / h
  const double stiffness_factor = 1.0 + beta_ / h;  // elastic + Rayleigh stiffness damping
  const bool corotational = options_.energy == Energy::kCorotational;
  Eigen::Vector3d force;
  Eigen::Matrix3d hessian;
  if (corotational) {
    // With R held over the step the forces are affine in x, so (1 + beta/h) f(x) -
    // (beta/h) f(x_t) is f at x + (beta/h)(x - x_t): one pass. The Hessian is constant over the
    // step: summed in the first iteration, kept for the others.
    const VertexBlock elastic = vertex_block(i, first_iteration);
    if (first_iteration) elastic_hessian_[i] = elastic.hessian;
    force = elastic.force;
    hessian = stiffness_factor * elastic_hessian_[i];
  } else {
    const VertexBlock elastic = vertex_block(i, true);
    force = stiffness_factor * elastic.force;
    if (beta_ > 0.0) force -= (beta_ / h) * vec_at(start_force_.data(), i);
    hessian = stiffness_factor * elastic.hessian;
  }
  hessian.diagonal().array() += inertia + mass_damping;
  const Eigen::Vector3d x = vec_at(positions, i);
  force -= inertia * (x - vec_at(inertia_target_.data(), i)) +
           mass_damping * (x - vec_at(start_.data(), i));
  const double det = hessian.determinant();
  const double scale = hessian.trace() / 3.0;
  if (!(det > kSingularRatio * scale * scale * scale)) {  // also NaN
    ++tallies_[worker].skipped;
    return;
  }
  const Eigen::Vector3d dx = hessian.inverse() * force;  // closed-form 3x3 inverse
  for (int k = 0; k < 3; ++k) positions[3 * size_t{i} + k] += dx[k];
  // Each tet's F follows its corner by a rank-one change (scaled as the cache is blended): no
  // other vertex of this colour is in these tets, so no other update writes them now.
  const Eigen::Vector3d change = (corotational ? stiffness_factor : 1.0) * dx;
  for (uint32_t k = incidence_start_[i]; k < incidence_start_[i + 1]; ++k) {
    const Incidence& inc = incidence_[k];
    TetFrame& frame = frames_[inc.tet];
    const Eigen::Vector3d w =
        corotational ? Eigen::Vector3d(frame.rotation.transpose() * change) : change;
    double* cached = frame.deformation.data();  // column-major: (r, c) at r + 3 c
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) cached[r + 3 * c] += w[r] * inc.gradient[c];
  }
}

void VbdModel::update_rotations(const double* positions) noexcept {
  for_each(static_cast<uint32_t>(tets_.size()), kTetGrain, [&](uint32_t e, uint32_t) {
    Eigen::Quaterniond q = step_rotation_[e];
    corotational::polar_rotation(deformation(e, positions), q, kPolarIterations);
    step_rotation_[e] = q;
    frames_[e].rotation = q.toRotationMatrix();
  });
}

uint32_t VbdModel::step(tacta_body_state& state, double dt) noexcept {
  h_ = dt;
  const double h = dt;
  double* x = state.positions;
  double* v = state.velocities;
  const double* f_ext = state.external_forces;
  const bool corotational = options_.energy == Energy::kCorotational;
  // x_t, the inertial target y and the initial guess (paper, section 3.6: the adaptive guess
  // keeps the part of the last acceleration along the external one, within [0, |a_ext|]).
  for (uint32_t i = 0; i < node_count_; ++i) {
    const size_t b = 3 * size_t{i};
    for (int k = 0; k < 3; ++k) start_[b + k] = inertia_target_[b + k] = x[b + k];
    if (fixed_[i]) continue;
    const Eigen::Vector3d vt = vec_at(v, i), a_ext = vec_at(f_ext, i) / masses_[i];
    Eigen::Vector3d guess_acceleration = a_ext;
    if (options_.initial_guess == InitialGuess::kPrevious) {
      guess_acceleration.setZero();
    } else if (options_.initial_guess == InitialGuess::kAdaptive && history_) {
      const double norm = a_ext.norm();
      const Eigen::Vector3d a_last = (vt - vec_at(previous_velocity_.data(), i)) / h;
      const double along = norm > 0.0 ? a_last.dot(a_ext) / norm : 0.0;
      guess_acceleration = a_ext * (norm > 0.0 ? std::clamp(along, 0.0, norm) / norm : 0.0);
    }
    for (int k = 0; k < 3; ++k) {
      inertia_target_[b + k] += h * vt[k] + h * h * a_ext[k];
      x[b + k] += h * vt[k] + h * h * guess_acceleration[k];
      previous_velocity_[b + k] = vt[k];
    }
  }
  history_ = true;
  // Per step: the rotations at x_t (corotational), or, for Neo-Hookean's Rayleigh stiffness
  // damping, each free vertex's elastic force at x_t.
  if (corotational) {
    update_rotations(start_.data());
  } else if (beta_ > 0.0) {
    refresh_deformations(start_.data(), 0.0);
    for_each(static_cast<uint32_t>(colour_vertices_.size()), kVertexGrain,
             [&](uint32_t k, uint32_t) {
               const uint32_t i = colour_vertices_[k];
               const Eigen::Vector3d f = vertex_block(i, false).force;
               for (int c = 0; c < 3; ++c) start_force_[3 * size_t{i} + c] = f[c];
             });
  }

  const int iterations = options_.iterations;
  const double rho = options_.chebyshev_rho;
  const bool chebyshev = rho > 0.0 && iterations > 1;
  if (chebyshev) std::copy(x, x + 3 * size_t{node_count_}, chebyshev_prev_.begin());
  double omega = 1.0;
  // Corotational: the forces at x + (beta/h)(x - x_t) (see update_vertex), so the cache holds
  // R^T F there. Taken afresh each iteration: Chebyshev moves every node, and rounding cannot
  // pile up.
  const double blend = corotational ? beta_ / h : 0.0;
  for (int it = 1; it <= iterations; ++it) {
    refresh_deformations(x, blend);
    for (uint32_t c = 0; c + 1 < colour_start_.size(); ++c) {
      const uint32_t* vertices = colour_vertices_.data() + colour_start_[c];
      for_each(
          colour_start_[c + 1] - colour_start_[c], kVertexGrain,
          [&](uint32_t k, uint32_t worker) { update_vertex(vertices[k], x, worker, it == 1); });
    }
    if (!chebyshev) continue;
    // Chebyshev semi-iterative acceleration (Wang 2015, as the paper uses it):
    // x^(k) = omega_k (x_bar^(k) - x^(k-2)) + x^(k-2); held nodes have x = x^(k-2).
    omega = it == 1 ? 1.0 : it == 2 ? 2.0 / (2.0 - rho * rho) : 4.0 / (4.0 - rho * rho * omega);
    for_each(node_count_, kNodeGrain, [&](uint32_t i, uint32_t) {
      for (size_t k = 3 * size_t{i}; k < 3 * size_t{i} + 3; ++k) {
        if (it > 1) x[k] = omega * (x[k] - chebyshev_prev2_[k]) + chebyshev_prev2_[k];
        chebyshev_prev2_[k] = chebyshev_prev_[k];
        chebyshev_prev_[k] = x[k];
      }
    });
  }
  for (uint32_t i = 0; i < node_count_; ++i)
    for (size_t k = 3 * size_t{i}; k < 3 * size_t{i} + 3; ++k)
      v[k] = fixed_[i] ? 0.0 : (x[k] - start_[k]) / h;
  return guard_.check(x, v);
}

void VbdModel::begin(const tacta_body_state& state, double /*dt*/) noexcept {
  history_ = false;
  // Converge the rotations now, from identity, so the first step starts warm.
  std::fill(step_rotation_.begin(), step_rotation_.end(), Eigen::Quaterniond::Identity());
  update_rotations(state.positions);
}

double VbdModel::elastic_energy(const double* positions) noexcept {
  const Lame lame{lambda_, mu_};
  double energy = 0.0;
  for (uint32_t e = 0; e < tets_.size(); ++e) {
    const Eigen::Matrix3d f = deformation(e, positions);
    double density = 0.0;
    if (options_.energy == Energy::kCorotational) {
      corotational::polar_rotation(f, query_rotation_[e], kPolarIterations);
      density = corotational_energy_density(f, query_rotation_[e].toRotationMatrix(), lame);
    } else {
      density = neo_hookean_energy_density(f, lame, kMinVolumeRatio);
    }
    energy += tets_[e].volume * density;
  }
  return energy;
}

void VbdModel::internal_forces(const double* positions, double* forces) noexcept {
  std::fill_n(forces, 3 * size_t{node_count_}, 0.0);
  const Lame lame{lambda_, mu_};
  for (uint32_t e = 0; e < tets_.size(); ++e) {
    const TetRest& t = tets_[e];
    const Eigen::Matrix3d f = deformation(e, positions);
    Eigen::Matrix3d stress;
    if (options_.energy == Energy::kCorotational) {
      corotational::polar_rotation(f, query_rotation_[e], kPolarIterations);
      stress = corotational_stress(f, query_rotation_[e].toRotationMatrix(), lame);
    } else {
      stress = neo_hookean_stress(f, lame, kMinVolumeRatio);
    }
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector3d fa = -t.volume * (stress * corner_gradient(t, a));
      for (int k = 0; k < 3; ++k) forces[3 * size_t{t.nodes[a]} + k] += fa[k];
    }
  }
}

void VbdModel::state_fields(StateIo& io) {
  io.vector(step_rotation_, "step_rotation");
  io.vector(query_rotation_, "query_rotation");
  io.vector(previous_velocity_, "previous_velocity");
  io.value(history_, "history");
  uint64_t skipped = skipped_updates();
  io.value(skipped, "skipped_vertex_updates");
  if (!io.loading()) return;
  for (WorkerTally& t : tallies_) t.skipped = 0;
  tallies_[0].skipped = skipped;
}

uint64_t VbdModel::skipped_updates() const {
  uint64_t total = 0;
  for (const WorkerTally& t : tallies_) total += t.skipped;
  return total;
}

}  // namespace tacta::models::vbd
