// What the haptic proxy's queries need of one collision surface per tick without refitting its
// whole hierarchy: the hierarchy is refit a slice of elements per tick, round-robin (the collision
// plugin's update_elements), and the queries widen their search by how far any vertex may have
// moved since its element's box was computed: the largest node move of each tick over the last
// round of slices, times the surface's weight bound (a vertex is a weighted sum of nodes).
// A margin past its cap (a fast body) asks for a whole refit instead. No allocation per tick.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tacta {

class SurfaceFreshness {
 public:
  static constexpr uint32_t kSliceElements = 256;  // elements refit per tick

  // node_count: the body's nodes; triangles (3 per triangle) over positions (3 per vertex, m):
  // the surface as it is now; weight_bound: the largest sum of |weight| of a vertex over the
  // nodes it follows (1: vertices are nodes); margin_cap: m.
  SurfaceFreshness(size_t node_count, const uint32_t* triangles, uint32_t triangle_count,
                   const double* positions, double weight_bound, double margin_cap);

  // Every box was just computed from `nodes` (3 per node, m): the margin restarts at 0.
  void reset(const double* nodes) noexcept;
  // Once a tick before the proxy's queries: takes in the nodes' largest move since the last
  // call. False when the margin is past its cap: the caller refits everything and calls reset.
  bool advance(const double* nodes) noexcept;
  // The triangles to refit this tick (count of them), round-robin over spatially compact slices:
  // consecutive in Morton order of their centroids, so a slice's ancestors in a hierarchy are few.
  const uint32_t* next_slice(uint32_t& count) noexcept;
  double margin() const noexcept { return margin_; }  // m
  double margin_cap() const noexcept { return margin_cap_; }

 private:
  std::vector<double> last_nodes_;  // 3 per node, m: at the last advance or reset
  std::vector<double> moves_;       // one per tick of the last round of slices, m
  size_t next_move_ = 0;
  std::vector<uint32_t> order_;  // triangle ids in Morton order
  uint32_t next_first_ = 0;
  double weight_bound_ = 1.0;
  double margin_cap_ = 0.0;
  double margin_ = 0.0;
};

}  // namespace tacta
