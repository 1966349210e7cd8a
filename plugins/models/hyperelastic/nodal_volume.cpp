#include "nodal_volume.hpp"

#include <algorithm>
#include <cmath>

namespace tacta::models::hyperelastic {

namespace {
constexpr int kPairA[10] = {0, 0, 0, 0, 1, 1, 1, 2, 2, 3};
constexpr int kPairB[10] = {0, 1, 2, 3, 1, 2, 3, 2, 3, 3};

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& w) {  // [w]x: [w]x y = w x y
  Eigen::Matrix3d m;
  m << 0.0, -w[2], w[1], w[2], 0.0, -w[0], -w[1], w[0], 0.0;
  return m;
}

VolumetricDerivatives exact_volumetric(const MaterialConstants& m, double j) {
  if (m.law == MaterialLaw::kMooneyRivlin)
    return {0.5 * m.bulk * (j - 1.0) * (j - 1.0), m.bulk * (j - 1.0), m.bulk};
  const double log_j = std::log(j);
  return {0.5 * m.lambda * log_j * log_j, m.lambda * log_j / j, m.lambda * (1.0 - log_j) / (j * j)};
}

// The sorted unique nodes of the elements around each node (CSR), from 4 nodes per element.
void build_stars(uint32_t node_count, std::span<const uint32_t> tets, std::vector<uint32_t>& starts,
                 std::vector<uint32_t>& nodes) {
  std::vector<std::vector<uint32_t>> star(node_count);
  for (size_t e = 0; e + 3 < tets.size(); e += 4)
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) star[tets[e + a]].push_back(tets[e + b]);
  starts.assign(1, 0);
  nodes.clear();
  for (auto& s : star) {
    std::sort(s.begin(), s.end());
    s.erase(std::unique(s.begin(), s.end()), s.end());
    nodes.insert(nodes.end(), s.begin(), s.end());
    starts.push_back(static_cast<uint32_t>(nodes.size()));
  }
}
}  // namespace

bool has_volumetric_term(MaterialLaw law) { return law != MaterialLaw::kStVenantKirchhoff; }

MaterialConstants without_volumetric_term(MaterialConstants material) {
  if (material.law == MaterialLaw::kMooneyRivlin)
    material.bulk = 0.0;
  else
    material.lambda = 0.0;
  return material;
}

VolumetricDerivatives volumetric_derivatives(const MaterialConstants& material, double j) {
  const double floor = material.min_stretch;
  if (j >= floor) return exact_volumetric(material, j);
  VolumetricDerivatives d = exact_volumetric(material, floor);
  d.second = std::max(d.second, 0.0);
  const double offset = j - floor;
  d.energy += d.first * offset + 0.5 * d.second * offset * offset;
  d.first += d.second * offset;
  return d;
}

std::vector<uint32_t> NodalVolumeTerm::coupled_pairs(uint32_t node_count,
                                                     std::span<const uint32_t> tets) {
  std::vector<uint32_t> starts, nodes, pairs;
  build_stars(node_count, tets, starts, nodes);
  for (uint32_t i = 0; i < node_count; ++i)
    for (uint32_t p = starts[i]; p < starts[i + 1]; ++p)
      for (uint32_t r = p + 1; r < starts[i + 1]; ++r) {
        pairs.push_back(nodes[p]);
        pairs.push_back(nodes[r]);
      }
  return pairs;
}

NodalVolumeTerm::NodalVolumeTerm(uint32_t node_count, std::span<const TetRest> elements,
                                 const MaterialConstants& material)
    : elements_(elements), material_(material) {
  std::vector<uint32_t> tets;
  tets.reserve(4 * elements.size());
  for (const TetRest& e : elements) tets.insert(tets.end(), e.nodes, e.nodes + 4);
  build_stars(node_count, tets, star_starts_, star_nodes_);
  rest_volume_.assign(node_count, 0.0);
  std::vector<std::vector<uint32_t>> adjacent(node_count);
  for (uint32_t e = 0; e < elements.size(); ++e)
    for (const uint32_t a : elements[e].nodes) {
      adjacent[a].push_back(e);
      rest_volume_[a] += 0.25 * elements[e].volume;
    }
  entry_starts_.assign(1, 0);
  size_t largest_star = 0;
  for (uint32_t i = 0; i < node_count; ++i) {
    const auto star_begin = star_nodes_.begin() + star_starts_[i];
    const auto star_end = star_nodes_.begin() + star_starts_[i + 1];
    largest_star = std::max(largest_star, static_cast<size_t>(star_end - star_begin));
    for (const uint32_t e : adjacent[i]) {
      entry_elements_.push_back(e);
      for (const uint32_t a : elements[e].nodes)
        entry_positions_.push_back(
            static_cast<uint32_t>(std::lower_bound(star_begin, star_end, a) - star_begin));
    }
    entry_starts_.push_back(static_cast<uint32_t>(entry_elements_.size()));
  }
  deformation_.resize(elements.size());
  volume_gradient_.resize(4 * elements.size());
  element_pressure_.assign(elements.size(), 0.0);
  volume_.assign(node_count, 0.0);
  pressure_.assign(node_count, 0.0);
  curvature_.assign(node_count, 0.0);
  star_gradient_.resize(largest_star);
}

void NodalVolumeTerm::bind(const sparse::BlockSparseMatrix& matrix) {
  pair_starts_.assign(1, 0);
  pair_slots_.clear();
  for (uint32_t i = 0; i + 1 < star_starts_.size(); ++i) {
    for (uint32_t p = star_starts_[i]; p < star_starts_[i + 1]; ++p)
      for (uint32_t r = p; r < star_starts_[i + 1]; ++r)
        pair_slots_.push_back(matrix.block_index(star_nodes_[p], star_nodes_[r]));
    pair_starts_.push_back(static_cast<uint32_t>(pair_slots_.size()));
  }
}

double NodalVolumeTerm::evaluate(const double* x) noexcept {
  std::fill(volume_.begin(), volume_.end(), 0.0);
  for (size_t e = 0; e < elements_.size(); ++e) {
    const TetRest& element = elements_[e];
    Eigen::Matrix3d& f = deformation_[e];  // F = sum_a x_a grad_a^T
    f.setZero();
    for (int a = 0; a < 4; ++a)
      f.noalias() += node_position(x, element.nodes[a]) *
                     Eigen::Map<const Eigen::Vector3d>(element.gradients[a]).transpose();
    // v_e = V_e det F; dv_e/dx_a = V_e cof(F) grad_a, cof(F) = [f1 x f2, f2 x f0, f0 x f1].
    Eigen::Matrix3d cofactor;
    cofactor.col(0) = f.col(1).cross(f.col(2));
    cofactor.col(1) = f.col(2).cross(f.col(0));
    cofactor.col(2) = f.col(0).cross(f.col(1));
    const double v = element.volume * f.col(0).dot(cofactor.col(0));
    for (int a = 0; a < 4; ++a) {
      volume_gradient_[4 * e + a] =
          element.volume * (cofactor * Eigen::Map<const Eigen::Vector3d>(element.gradients[a]));
      volume_[element.nodes[a]] += 0.25 * v;
    }
  }
  double energy = 0.0;
  for (size_t i = 0; i < volume_.size(); ++i) {
    if (rest_volume_[i] <= 0.0) continue;  // a node in no element
    const VolumetricDerivatives u = volumetric_derivatives(material_, volume_[i] / rest_volume_[i]);
    energy += rest_volume_[i] * u.energy;
    pressure_[i] = u.first;
    curvature_[i] = u.second / rest_volume_[i];
  }
  for (size_t e = 0; e < elements_.size(); ++e) {
    double p = 0.0;
    for (const uint32_t a : elements_[e].nodes) p += pressure_[a];
    element_pressure_[e] = 0.25 * p;
  }
  return energy;
}

void NodalVolumeTerm::add_forces(double* forces) const noexcept {
  for (size_t e = 0; e < elements_.size(); ++e)
    for (int a = 0; a < 4; ++a) {
      const Eigen::Vector3d f = -element_pressure_[e] * volume_gradient_[4 * e + a];
      for (int c = 0; c < 3; ++c) forces[3 * elements_[e].nodes[a] + c] += f[c];
    }
}

void NodalVolumeTerm::add_tangent(sparse::BlockSparseMatrix& matrix, double scale,
                                  bool project) noexcept {
  for (size_t i = 0; i + 1 < star_starts_.size(); ++i) {
    const double c = scale * (project ? std::max(curvature_[i], 0.0) : curvature_[i]);
    if (c == 0.0) continue;
    const uint32_t size = star_starts_[i + 1] - star_starts_[i];
    std::fill_n(star_gradient_.begin(), size, Eigen::Vector3d::Zero());
    for (uint32_t k = entry_starts_[i]; k < entry_starts_[i + 1]; ++k)
      for (int a = 0; a < 4; ++a)
        star_gradient_[entry_positions_[4 * k + a]] +=
            0.25 * volume_gradient_[4 * entry_elements_[k] + a];
    const uint32_t* slot = &pair_slots_[pair_starts_[i]];
    for (uint32_t p = 0; p < size; ++p)
      for (uint32_t r = p; r < size; ++r, ++slot)
        Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(matrix.block(*slot)) +=
            c * star_gradient_[p] * star_gradient_[r].transpose();
  }
  if (project) return;
  // d2 v_e / dx_a dx_b = -V_e [F (grad_a x grad_b)]x (from d2 det F / dF_ij dF_kl =
  // e_ikm e_jln F_mn); zero for a = b.
  for (uint32_t e = 0; e < elements_.size(); ++e) {
    const TetRest& element = elements_[e];
    const uint32_t* slots = matrix.element_slots(e);
    for (int p = 0; p < 10; ++p) {
      int a = kPairA[p], b = kPairB[p];
      if (a == b) continue;
      if (element.nodes[a] > element.nodes[b]) std::swap(a, b);  // the stored block is (low, high)
      const Eigen::Vector3d w = Eigen::Map<const Eigen::Vector3d>(element.gradients[a])
                                    .cross(Eigen::Map<const Eigen::Vector3d>(element.gradients[b]));
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(matrix.block(slots[p])) -=
          (scale * element_pressure_[e] * element.volume) * cross_matrix(deformation_[e] * w);
    }
  }
}

}  // namespace tacta::models::hyperelastic
