// HyperelasticModel: construction and the element pass (energy, forces, tangent assembly).
// The Newton iterations that use them are in newton_solve.cpp.
#include "hyperelastic_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "invariant_stress.hpp"
#include "isotropic_element.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::hyperelastic {

namespace {
constexpr int kPairA[10] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3};
constexpr int kPairB[10] = {0, 1, 2, 3, 1, 2, 3, 2, 3, 3};

// f_a = -V P grad_a onto the element's nodes, N.
void scatter_forces(const TetRest& element, const Eigen::Matrix3d& stress, double* forces) {
  for (int a = 0; a < 4; ++a) {
    const Eigen::Vector3d f =
        -element.volume * (stress * Eigen::Map<const Eigen::Vector3d>(element.gradients[a]));
    for (int c = 0; c < 3; ++c) forces[3 * element.nodes[a] + c] += f[c];
  }
}

// The matrix pattern beyond the tets' own pairs: the nodal volumes' 1-ring coupling.
std::vector<uint32_t> extra_pairs(const tacta_mesh_view& mesh, const Options& options) {
  if (options.volumetric == Volumetric::kElement) return {};
  return NodalVolumeTerm::coupled_pairs(
      mesh.node_count, std::span<const uint32_t>(mesh.tets, 4 * size_t{mesh.tet_count}));
}
}  // namespace

HyperelasticModel::HyperelasticModel(const tacta_mesh_view& mesh, const tacta_material& material,
                                     std::span<const double> masses, std::span<const uint8_t> fixed,
                                     const Options& options)
    : node_count_(mesh.node_count),
      masses_(masses.begin(), masses.end()),
      fixed_(fixed.begin(), fixed.end()),
      options_(options),
      element_material_(options.material),
      guard_(mesh),
      matrix_(mesh.node_count, std::span<const uint32_t>(mesh.tets, 4 * size_t{mesh.tet_count}),
              extra_pairs(mesh, options)),
      damping_(mesh.node_count, std::span<const uint32_t>(mesh.tets, 4 * size_t{mesh.tet_count}),
               extra_pairs(mesh, options)),
      rayleigh_mass_(material.rayleigh_mass),
      rayleigh_stiffness_(material.rayleigh_stiffness) {
  // The moduli arrive in options.material (the plugin derives them from E, nu or its keys).
  if (mesh.tet_count == 0)
    throw std::invalid_argument("hyperelastic needs a tetrahedral mesh (the mesh has no tets)");
  if (masses_.size() != node_count_)
    throw std::invalid_argument("hyperelastic: expected one mass per node");
  const bool any_fixed = std::find(fixed_.begin(), fixed_.end(), uint8_t{1}) != fixed_.end();
  if (options_.mode == SolveMode::kStatic && !any_fixed)
    throw std::invalid_argument(
        "hyperelastic: solve: static needs fixed nodes (a free body has "
        "no equilibrium under a net load)");
  check_free_node_masses("hyperelastic", masses_, fixed_);
  elements_.reserve(mesh.tet_count);
  for (uint32_t e = 0; e < mesh.tet_count; ++e)
    elements_.push_back(
        checked_tet_rest("hyperelastic", mesh.rest_positions, node_count_, mesh.tets, e));
  if (options_.volumetric == Volumetric::kNodalAverage) {
    if (!has_volumetric_term(options_.material.law))
      throw std::invalid_argument(
          "hyperelastic: volumetric: nodal_average needs a law with a "
          "volumetric term U(J) (neo_hookean or mooney_rivlin), not stvk");
    element_material_ = without_volumetric_term(options_.material);
    nodal_ = std::make_unique<NodalVolumeTerm>(node_count_, elements_, options_.material);
    nodal_->bind(matrix_);
  }
  const size_t n = 3 * static_cast<size_t>(node_count_);
  for (auto* buffer :
       {&forces_, &residual_, &correction_, &predicted_, &start_, &trial_, &loads_,
        &equilibrium_loads_, &scratch_, &product_, &last_correction_, &trial_residual_})
    buffer->assign(n, 0.0);
  weights_.assign(node_count_, 0.0);
  assembled_deformation_.assign(elements_.size(), Eigen::Matrix3d::Identity());
  // With nodal volumes the step stays serial: their term (nodal_volume.hpp) is serial, and the
  // solve's row-parallel products read both triangles of its wide matrix (a node's 1-ring's
  // 1-ring), doubling reads already bound by memory; threaded, that step measured no faster, or
  // slower (docs/BENCHMARKS.md, *hyperelastic on the workers*).
  const tacta_host_services* host = nodal_ ? nullptr : options_.host;
  options_.solver.host = host;
  solver_ = std::make_unique<sparse::SafeSolver>(matrix_, options_.solver);
  if (host != nullptr) tile_elements(mesh.rest_positions);
  rows_ = sparse::RowTeam(host, node_count_, sparse::ConjugateGradientSolver::kMinThreadedNodes);
  matrix_.apply_fixed(fixed_);  // builds the list of blocks to clear, while allocation is allowed
}

HyperelasticModel::~HyperelasticModel() = default;

double HyperelasticModel::element_pass(const double* x, double* forces, double scale) noexcept {
  PassTally tally{0.0, deformation_change_, false};
  if (nodal_) {
    tally.energy += nodal_->evaluate(x);
    if (forces != nullptr) nodal_->add_forces(forces);
    if (scale != 0.0) nodal_->add_tangent(matrix_, scale, options_.project_tangent);
  }
  // Tiles only within step() (and for tile_queries): a query may come from another thread (a
  // cut being prepared), which must not take the workers from the tick.
  if (!tiles_.empty() && (stepping_ || options_.tile_queries) &&
      tacta_host_workers_here(options_.host) >= 2) {
    tiled_elements(x, forces, scale, tally);
  } else {  // in mesh order: a body stepped in a group, or a host with one worker
    for (uint32_t e = 0; e < elements_.size(); ++e)
      if (!add_element(e, x, forces, scale, tally)) break;
  }
  inverted_ = tally.inverted;
  deformation_change_ = tally.change;
  return tally.energy;
}

bool HyperelasticModel::add_element(uint32_t e, const double* x, double* forces, double scale,
                                    PassTally& tally) noexcept {
  const MaterialConstants& material = element_material_;
  const Element& element = elements_[e];
  Eigen::Matrix3d deformation = Eigen::Matrix3d::Zero();  // F = sum_a x_a grad_a^T
  for (int a = 0; a < 4; ++a)
    deformation.noalias() += node_position(x, element.nodes[a]) *
                             Eigen::Map<const Eigen::Vector3d>(element.gradients[a]).transpose();
  if (record_deformation_) assembled_deformation_[e] = deformation;
  if (track_change_) {
    tally.change = std::max(tally.change, (deformation - assembled_deformation_[e]).squaredNorm());
    // The lagged system is ruled out: the caller assembles a fresh tangent, which computes
    // the forces again, so the rest of this pass would be wasted.
    if (tally.change > options_.tangent_reuse_change * options_.tangent_reuse_change) return false;
  }
  if (scale == 0.0) {  // no tangent: the invariants give psi and P without an SVD
    double psi = 0.0;
    Eigen::Matrix3d stress;
    if (invariant_stress(material, deformation, psi, forces != nullptr ? &stress : nullptr)) {
      tally.energy += element.volume * psi;
      if (forces != nullptr) scatter_forces(element, stress, forces);
      return true;
    }
  }
  const StretchFrame frame = rotation_variant_svd(deformation);
  if (frame.sigma[2] <= 0.0) tally.inverted = true;
  if (forces == nullptr && scale == 0.0) {
    tally.energy += element.volume * clamped_stretch_energy(material, frame.sigma);
    return true;
  }
  const StretchDerivatives psi = clamped_stretch_derivatives(material, frame.sigma);
  tally.energy += element.volume * psi.energy;
  if (forces != nullptr) scatter_forces(element, first_piola(frame, psi), forces);
  if (scale == 0.0) return true;
  const DiagonalTangent tangent = diagonal_tangent(frame.sigma, psi, options_.project_tangent);
  Eigen::Vector3d w[4];  // V^T grad_a
  for (int a = 0; a < 4; ++a)
    w[a] = frame.v.transpose() * Eigen::Map<const Eigen::Vector3d>(element.gradients[a]);
  Eigen::Matrix3d blocks[10];
  element_stiffness(frame, tangent, w, scale * element.volume, blocks);
  const uint32_t* slots = matrix_.element_slots(e);
  for (int p = 0; p < 10; ++p) {
    Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> stored(matrix_.block(slots[p]));
    // The stored block is (low node, high node): K_ba = K_ab^T when a's node is the higher.
    if (element.nodes[kPairA[p]] > element.nodes[kPairB[p]])
      stored += blocks[p].transpose();
    else
      stored += blocks[p];
  }
  return true;
}

double HyperelasticModel::elastic_energy(const double* positions) noexcept {
  return element_pass(positions, nullptr, 0.0);
}

void HyperelasticModel::internal_forces(const double* positions, double* forces) noexcept {
  std::fill_n(forces, 3 * static_cast<size_t>(node_count_), 0.0);
  element_pass(positions, forces, 0.0);
}

const sparse::BlockSparseMatrix& HyperelasticModel::assemble_stiffness(
    const double* positions) noexcept {
  system_valid_ = false;
  matrix_.set_zero();
  element_pass(positions, nullptr, 1.0);
  return matrix_;
}

void HyperelasticModel::node_stress(const double* positions, double* von_mises) noexcept {
  std::fill_n(von_mises, node_count_, 0.0);
  std::fill(weights_.begin(), weights_.end(), 0.0);
  for (const Element& element : elements_) {
    Eigen::Matrix3d deformation = Eigen::Matrix3d::Zero();
    for (int a = 0; a < 4; ++a)
      deformation.noalias() += node_position(positions, element.nodes[a]) *
                               Eigen::Map<const Eigen::Vector3d>(element.gradients[a]).transpose();
    const StretchFrame frame = rotation_variant_svd(deformation);
    const StretchDerivatives psi = clamped_stretch_derivatives(element_material_, frame.sigma);
    // Cauchy stress sigma = P F^T / J, in the principal frame: g_i s_i / J.
    const double j = std::max(std::abs(frame.sigma.prod()), 1e-12);
    const Eigen::Vector3d s = psi.gradient.cwiseProduct(frame.sigma) / j;
    const double vm =
        std::sqrt(0.5 * ((s[0] - s[1]) * (s[0] - s[1]) + (s[1] - s[2]) * (s[1] - s[2]) +
                         (s[2] - s[0]) * (s[2] - s[0])));
    for (uint32_t a : element.nodes) {  // volume-weighted average over adjacent elements
      von_mises[a] += element.volume * vm;
      weights_[a] += element.volume;
    }
  }
  for (uint32_t i = 0; i < node_count_; ++i)
    if (weights_[i] > 0.0) von_mises[i] /= weights_[i];
}

}  // namespace tacta::models::hyperelastic
