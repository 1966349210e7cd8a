#include "tacta/models/edge_graph.hpp"

#include <stdexcept>
#include <string>

namespace tacta::models {

EdgeGraph EdgeGraph::from_mesh(const tacta_mesh_view& mesh) {
  EdgeGraph g;
  g.offset.assign(mesh.node_count + 1u, 0u);
  for (uint32_t e = 0; e < mesh.edge_count; ++e) {
    const uint32_t a = mesh.edges[2 * e], b = mesh.edges[2 * e + 1];
    if (a >= mesh.node_count || b >= mesh.node_count || a == b)
      throw std::invalid_argument("mesh edge " + std::to_string(e) + " (" + std::to_string(a) +
                                  ", " + std::to_string(b) + ") is invalid for " +
                                  std::to_string(mesh.node_count) + " nodes");
    ++g.offset[a + 1];
    ++g.offset[b + 1];
  }
  for (uint32_t i = 0; i < mesh.node_count; ++i) g.offset[i + 1] += g.offset[i];
  g.neighbour.resize(2u * mesh.edge_count);
  g.edge.resize(2u * mesh.edge_count);
  std::vector<uint32_t> fill(g.offset.begin(), g.offset.end() - 1);
  for (uint32_t e = 0; e < mesh.edge_count; ++e) {
    const uint32_t a = mesh.edges[2 * e], b = mesh.edges[2 * e + 1];
    g.neighbour[fill[a]] = b;
    g.edge[fill[a]++] = e;
    g.neighbour[fill[b]] = a;
    g.edge[fill[b]++] = e;
  }
  return g;
}

uint32_t EdgeGraph::find_edge(uint32_t a, uint32_t b) const {
  for (uint32_t k = offset[a]; k < offset[a + 1]; ++k)
    if (neighbour[k] == b) return edge[k];
  return UINT32_MAX;
}

}  // namespace tacta::models
