#include "tacta/models/tet_geometry.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace tacta::models {

double tet_signed_volume(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  return (x1 - x0).dot((x2 - x0).cross(x3 - x0)) / 6.0;
}

std::array<Vec3, 4> tet_shape_gradients(const Vec3& x0, const Vec3& x1, const Vec3& x2,
                                        const Vec3& x3) {
  Mat3 edges;
  edges.col(0) = x1 - x0;
  edges.col(1) = x2 - x0;
  edges.col(2) = x3 - x0;
  // Rows of the inverse edge matrix are the gradients of N_1..N_3 (barycentric coordinates).
  const Mat3 inverse = edges.inverse();
  std::array<Vec3, 4> g;
  for (int j = 0; j < 3; ++j) g[static_cast<size_t>(j) + 1] = inverse.row(j).transpose();
  g[0] = -(g[1] + g[2] + g[3]);
  return g;
}

std::vector<double> lumped_tet_masses(std::span<const double> positions,
                                      std::span<const uint32_t> tets, double density) {
  std::vector<double> masses(positions.size() / 3, 0.0);
  for (size_t t = 0; t + 3 < tets.size(); t += 4) {
    const double volume = std::abs(tet_signed_volume(node_position(positions.data(), tets[t]),
                                                     node_position(positions.data(), tets[t + 1]),
                                                     node_position(positions.data(), tets[t + 2]),
                                                     node_position(positions.data(), tets[t + 3])));
    for (size_t k = 0; k < 4; ++k) masses[tets[t + k]] += density * volume / 4.0;
  }
  return masses;
}

double min_tet_edge_length(std::span<const double> positions, std::span<const uint32_t> tets) {
  double shortest = std::numeric_limits<double>::infinity();
  for (size_t t = 0; t + 3 < tets.size(); t += 4)
    for (size_t a = 0; a < 4; ++a)
      for (size_t b = a + 1; b < 4; ++b)
        shortest = std::min(shortest, (node_position(positions.data(), tets[t + a]) -
                                       node_position(positions.data(), tets[t + b]))
                                          .norm());
  return shortest;
}

TetRest checked_tet_rest(const char* model, const double* rest_positions, uint32_t node_count,
                         const uint32_t* tets, uint32_t e) {
  TetRest tet;
  Vec3 x[4];
  for (int a = 0; a < 4; ++a) {
    tet.nodes[a] = tets[4 * size_t{e} + a];
    if (tet.nodes[a] >= node_count)
      throw std::invalid_argument(std::string(model) + ": tet " + std::to_string(e) +
                                  " names node " + std::to_string(tet.nodes[a]) +
                                  " but the mesh has " + std::to_string(node_count));
    x[a] = node_position(rest_positions, tet.nodes[a]);
  }
  tet.volume = tet_signed_volume(x[0], x[1], x[2], x[3]);
  if (!(tet.volume > 0.0))
    throw std::invalid_argument(std::string(model) + ": tet " + std::to_string(e) +
                                " has non-positive rest volume " + std::to_string(tet.volume) +
                                " m^3 (expected positive orientation)");
  const std::array<Vec3, 4> gradients = tet_shape_gradients(x[0], x[1], x[2], x[3]);
  for (int a = 0; a < 4; ++a)
    for (int c = 0; c < 3; ++c) tet.gradients[a][c] = gradients[a][c];
  return tet;
}

void check_free_node_masses(const char* model, std::span<const double> masses,
                            std::span<const uint8_t> fixed) {
  for (size_t i = 0; i < masses.size(); ++i)
    if (!(masses[i] > 0.0) && (fixed.empty() || !fixed[i]))
      throw std::invalid_argument(std::string(model) + ": node " + std::to_string(i) +
                                  " is free but has mass " + std::to_string(masses[i]) + " kg");
}

}  // namespace tacta::models
