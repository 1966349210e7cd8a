// The volumetric energy on nodally averaged volumes (average nodal pressure tets, Bonet &
// Burton 1998), which removes the volumetric locking of linear tets near incompressibility.
// Each node i owns a quarter of every adjacent tet: rest volume V_i = sum_e V_e / 4 and current
// volume v_i = sum_e v_e / 4, so J_i = v_i / V_i, and the energy sum_i V_i U(J_i) replaces the
// elements' own volumetric terms (the deviatoric part stays per element). One pressure per
// node instead of one per tet (a mesh has 5-6 times more tets than nodes): few enough volume
// constraints for a linear displacement field to bend without locking.
// Forces: element e feels the mean of its nodes' U'(J_i) as its pressure p_e, f_a = -p_e dv_e/dx_a.
// Tangent: sum_i U''(J_i) / V_i q_i q_i^T with q_i = dv_i/dx (couples node i's whole 1-ring:
// the matrix needs the pairs from coupled_pairs()), plus sum_e p_e d2 v_e/dx2 in the exact
// tangent. The projected tangent takes U'' >= 0 and drops that volume curvature (indefinite,
// and of the size of the pressure, not of the bulk modulus), so it stays positive semi-definite.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <span>
#include <vector>

#include "block_sparse.hpp"
#include "stretch_energy.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models::hyperelastic {

// Which laws have a volumetric term U(J) to average: neo_hookean (lambda/2 ln^2 J) and
// mooney_rivlin (K/2 (J - 1)^2); stvk's lambda/2 tr(E)^2 is not a function of J.
bool has_volumetric_term(MaterialLaw law);
// The law without its volumetric term (lambda or K set to 0): what stays per element.
MaterialConstants without_volumetric_term(MaterialConstants material);

struct VolumetricDerivatives {
  double energy = 0.0, first = 0.0, second = 0.0;  // U (Pa), dU/dJ (Pa), d2U/dJ2 (Pa)
};
// U(J) and its derivatives; below J = min_stretch (where ln J blows up, or a patch inverts)
// its Taylor expansion about min_stretch, with a curvature of at least zero.
VolumetricDerivatives volumetric_derivatives(const MaterialConstants& material, double j);

class NodalVolumeTerm {
 public:
  NodalVolumeTerm(uint32_t node_count, std::span<const TetRest> elements,
                  const MaterialConstants& material);
  // Every node pair in some node's 1-ring (2 indices each): extra pattern for the tangent.
  static std::vector<uint32_t> coupled_pairs(uint32_t node_count, std::span<const uint32_t> tets);
  // Maps the tangent's node pairs to the matrix's blocks (built with coupled_pairs()).
  void bind(const sparse::BlockSparseMatrix& matrix);

  // At positions x: element volumes, nodal J and pressures. Returns sum_i V_i U(J_i), J.
  double evaluate(const double* x) noexcept;
  // After evaluate(): adds the forces -p_e dv_e/dx, N.
  void add_forces(double* forces) const noexcept;
  // After evaluate(): adds scale * the volumetric tangent (see above) into matrix.
  void add_tangent(sparse::BlockSparseMatrix& matrix, double scale, bool project) noexcept;

 private:
  std::span<const TetRest> elements_;
  MaterialConstants material_;
  std::vector<double> rest_volume_;                 // V_i, m^3
  std::vector<uint32_t> star_starts_, star_nodes_;  // per node: sorted 1-ring (itself included)
  std::vector<uint32_t> entry_starts_, entry_elements_;  // per node: adjacent elements
  std::vector<uint32_t> entry_positions_;             // per entry: its 4 nodes' places in the star
  std::vector<uint32_t> pair_starts_, pair_slots_;    // per node: the star's pairs p <= r
  std::vector<Eigen::Matrix3d> deformation_;          // F per element
  std::vector<Eigen::Vector3d> volume_gradient_;      // dv_e/dx_a, 4 per element, m^2
  std::vector<double> volume_, pressure_;             // v_i (m^3), then U'(J_i) per node (Pa)
  std::vector<double> element_pressure_, curvature_;  // p_e (Pa); U''(J_i) / V_i (Pa/m^3)
  std::vector<Eigen::Vector3d> star_gradient_;        // scratch: q_i over the star, m^2
};

}  // namespace tacta::models::hyperelastic
