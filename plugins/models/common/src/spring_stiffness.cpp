#include "tacta/models/spring_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "tacta/models/edge_graph.hpp"
#include "tacta/models/lame.hpp"
#include "tacta/models/tet_geometry.hpp"

namespace tacta::models {

std::vector<double> edge_stiffness(const char* model, const tacta_mesh_view& mesh,
                                   const tacta_material& material, StiffnessRule rule) {
  const std::string name(model);
  const EdgeGraph graph = EdgeGraph::from_mesh(mesh);  // refuses an edge naming a missing node
  const double* rest = mesh.rest_positions;
  std::vector<double> length(mesh.edge_count);
  for (uint32_t e = 0; e < mesh.edge_count; ++e) {
    length[e] =
        (node_position(rest, mesh.edges[2 * e]) - node_position(rest, mesh.edges[2 * e + 1]))
            .norm();
    if (!(length[e] > 0))
      throw std::invalid_argument(name + ": edge " + std::to_string(e) + " has zero length");
  }
  const Lame lame = lame_from_young(material.youngs_modulus, material.poisson_ratio);
  std::vector<double> stiffness(mesh.edge_count, 0.0);  // N/m
  for (uint32_t t = 0; t < mesh.tet_count; ++t) {
    const uint32_t* tet = mesh.tets + 4 * static_cast<size_t>(t);
    Vec3 x[4];
    for (int k = 0; k < 4; ++k) {
      if (tet[k] >= mesh.node_count)
        throw std::invalid_argument(name + ": tet " + std::to_string(t) + " names node " +
                                    std::to_string(tet[k]) + " of " +
                                    std::to_string(mesh.node_count));
      x[k] = node_position(rest, tet[k]);
    }
    const double volume =
        std::abs(tet_signed_volume(x[0], x[1], x[2], x[3]));  // m^3, either orientation
    if (!(volume > 0))
      throw std::invalid_argument(name + ": tet " + std::to_string(t) + " has zero volume");
    const std::array<Vec3, 4> g = tet_shape_gradients(x[0], x[1], x[2], x[3]);
    for (int p = 0; p < 4; ++p)
      for (int q = p + 1; q < 4; ++q) {
        const uint32_t e = graph.find_edge(tet[p], tet[q]);
        if (e == UINT32_MAX)
          throw std::invalid_argument(name + ": an edge of tet " + std::to_string(t) +
                                      " is missing from mesh.edges");
        const double l2 = length[e] * length[e];
        stiffness[e] += rule == StiffnessRule::kVanGelder
                            ? material.youngs_modulus * volume / l2
                            : volume * ((lame.lambda + lame.mu) / l2 - lame.mu * g[p].dot(g[q]));
      }
  }
  for (double& k : stiffness) k = std::max(k, 0.0);
  return stiffness;
}

const char* stiffness_rule_name(StiffnessRule rule) {
  return rule == StiffnessRule::kVanGelder ? "van_gelder" : "fem_projection";
}

std::string median_and_range(std::vector<double> values) {
  if (values.empty()) return "none";
  std::sort(values.begin(), values.end());
  char text[96];
  std::snprintf(text, sizeof text, "median %.3g (min %.3g, max %.3g)", values[values.size() / 2],
                values.front(), values.back());
  return text;
}

}  // namespace tacta::models
