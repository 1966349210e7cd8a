// Geometry of linear tetrahedra at rest: volumes, shape-function gradients, lumped masses.
// Positions are flat arrays of 3 doubles per node (m); tets are 4 node indices each.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace tacta::models {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

inline Vec3 node_position(const double* positions, uint32_t node) {
  return Vec3(positions[3 * node], positions[3 * node + 1], positions[3 * node + 2]);
}

// Signed volume of (x0, x1, x2, x3), m^3: positive when det(x1-x0, x2-x0, x3-x0) > 0.
double tet_signed_volume(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3);

// Gradients of the four linear shape functions N_j (1/m). They sum to zero. Delingette's area
// vectors relate to them by m_j = -6 V grad N_j (twice the outward area vector of the face
// opposite vertex j).
std::array<Vec3, 4> tet_shape_gradients(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                        const Vec3& x3);

// One tet at rest as a model keeps it: node indices, shape-function gradients and volume.
struct TetRest {
  uint32_t nodes[4];
  double gradients[4][3];  // grad N_a, 1/m
  double volume;           // m^3
};
// Tet e of a mesh (4 node indices per tet), checked: nodes within node_count and a positive
// rest volume. Throws std::invalid_argument naming the model, the tet and what is wrong.
TetRest checked_tet_rest(const char* model, const double* rest_positions, uint32_t node_count,
                         const uint32_t* tets, uint32_t e);
// Every free node (fixed empty or 0) has a positive mass; else std::invalid_argument naming it.
void check_free_node_masses(const char* model, std::span<const double> masses,
                            std::span<const uint8_t> fixed);

// Lumped nodal masses (kg): each tet gives a quarter of rho * V to each of its nodes.
std::vector<double> lumped_tet_masses(std::span<const double> positions,
                                      std::span<const uint32_t> tets, double density);

// Smallest edge length over all tets (m), for stable-time-step estimates.
double min_tet_edge_length(std::span<const double> positions, std::span<const uint32_t> tets);

}  // namespace tacta::models
