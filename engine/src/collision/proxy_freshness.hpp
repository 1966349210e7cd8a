// What the haptic proxy's queries need of one collision surface per tick without refitting its
// whole hierarchy. The hierarchy's elements are cut into slices (runs of its element order); each
// slice keeps how far any of its vertices may have moved since its boxes were computed: the sum,
// over the ticks since, of the largest node move, times the surface's weight bound (a vertex is a
// weighted sum of nodes). The queries widen their search by the largest of these (the margin).
// While the margin is past its target the stalest slice is refit, one a tick; a still body costs
// nothing. A margin past its cap (a fast body) asks for a whole refit. No allocation per tick.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace tacta {

class SurfaceFreshness {
 public:
  static constexpr uint32_t kSliceElements = 128;  // elements refit per tick, at most

  // node_count: the body's nodes; element_count: the surface's triangles; weight_bound: the
  // largest sum of |weight| of a vertex over the nodes it follows (1: vertices are nodes);
  // margin_target, margin_cap: m.
  SurfaceFreshness(size_t node_count, uint32_t element_count, double weight_bound,
                   double margin_target, double margin_cap);

  // Every box was just computed from `nodes` (3 per node, m): the margin restarts at 0.
  void reset(const double* nodes) noexcept;
  // Once a tick before the proxy's queries: takes in the nodes' largest move since the last
  // call. False when the margin is past its cap: the caller refits everything and calls reset.
  bool advance(const double* nodes) noexcept;
  // The run [first, first + count) of the hierarchy's element order to refit this tick: the
  // stalest slice while the margin is past its target, else none (count 0). The margin then
  // assumes it was refit.
  void next_slice(uint32_t& first, uint32_t& count) noexcept;
  double margin() const noexcept { return margin_; }  // m
  double margin_cap() const noexcept { return margin_cap_; }

 private:
  void update_margin() noexcept;
  std::vector<double> last_nodes_;  // 3 per node, m: at the last advance or reset
  std::vector<double> drift_;       // per slice: node moves summed since it was refit, m
  uint32_t element_count_ = 0;
  double weight_bound_ = 1.0;
  double margin_target_ = 0.0;
  double margin_cap_ = 0.0;
  double margin_ = 0.0;
};

}  // namespace tacta
