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

// Lumped nodal masses (kg): each tet gives a quarter of rho * V to each of its nodes.
std::vector<double> lumped_tet_masses(std::span<const double> positions,
                                      std::span<const uint32_t> tets, double density);

// Smallest edge length over all tets (m), for stable-time-step estimates.
double min_tet_edge_length(std::span<const double> positions, std::span<const uint32_t> tets);

}  // namespace tacta::models
