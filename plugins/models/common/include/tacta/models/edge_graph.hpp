// Node adjacency from a mesh's unique edge list, in compressed rows: the neighbours of node i
// are neighbour[offset[i] .. offset[i+1]), each with the index of the edge that joins them.
#pragma once

#include <cstdint>
#include <vector>

#include "tacta/model_api.h"

namespace tacta::models {

struct EdgeGraph {
  std::vector<uint32_t> offset;     // node_count + 1
  std::vector<uint32_t> neighbour;  // 2 * edge_count
  std::vector<uint32_t> edge;       // 2 * edge_count: edge index of each (i, neighbour) entry

  uint32_t node_count() const {
    return offset.empty() ? 0u : static_cast<uint32_t>(offset.size() - 1);
  }
  uint32_t degree(uint32_t node) const { return offset[node + 1] - offset[node]; }

  // Throws std::invalid_argument naming the edge when an index is out of range or i == j.
  static EdgeGraph from_mesh(const tacta_mesh_view& mesh);
  // Edge index joining a and b, or UINT32_MAX when they are not neighbours.
  uint32_t find_edge(uint32_t a, uint32_t b) const;
};

}  // namespace tacta::models
