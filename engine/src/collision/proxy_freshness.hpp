// What the haptic proxy's queries need of one collision surface per tick without refitting its
// whole hierarchy. The hierarchy's elements are cut into slices (runs of its element order); each
// slice keeps how far any of its vertices may have moved since its boxes were computed: the
// longest path since, among the nodes its vertices follow, times the surface's weight bound (a
// vertex is a weighted sum of nodes). Each node sums its own path at every advance; the slices
// take their nodes' longest every few advances, and until then every slice adds the longest of all
// (pending). Until the slices' nodes are known (bind), every slice takes the body's largest node
// move. The queries widen their search by the largest drift (the margin). While the margin is
// past its target the stalest slice is refit, one an upkeep: a still body, or its still part,
// costs nothing. A path summed over ticks overstates where a jiggling node is, so before a slice is
// refit its nodes are measured against where they were at its last refit (a slice's worth of
// reads against a refit's worth of work): a slice still near its boxes takes that distance as its
// drift and is not refit. A margin past its cap (a fast body) asks for a whole refit. No
// allocation per tick.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace tacta {

class SurfaceFreshness {
 public:
  static constexpr uint32_t kSliceElements = 64;  // elements a slice refits

  // node_count: the body's nodes; element_count: the surface's triangles; weight_bound: the
  // largest sum of |weight| of a vertex over the nodes it follows (1: vertices are nodes);
  // margin_target, margin_cap: m.
  // nodes_per_vertex: how many nodes a vertex follows (4: an embedded surface's tet; 1: vertices
  // are nodes), which sizes the slices' node lists.
  SurfaceFreshness(size_t node_count, uint32_t element_count, double weight_bound,
                   double margin_target, double margin_cap, uint32_t nodes_per_vertex);

  // Every box was just computed from `nodes` (3 per node, m): the margin restarts at 0.
  void reset(const double* nodes) noexcept;
  // The nodes each slice follows, from the hierarchy's element order (element_count entries)
  // over `triangles` (3 per triangle) and `vertex_nodes` (nodes_per_vertex per vertex, or null:
  // vertices are nodes). Again after each rebuild, which may reorder. No allocation.
  void bind(const uint32_t* order, const uint32_t* triangles,
            const uint32_t* vertex_nodes) noexcept;
  // Before the proxy's queries and in the upkeep after the write (twice a tick): takes in the
  // nodes' moves since the last call. False when the margin is past its cap: the caller refits
  // everything and calls reset.
  bool advance(const double* nodes) noexcept;
  // The run [first, first + count) of the hierarchy's element order to refit this tick, from the
  // nodes as the last advance read them: the stalest slice while the margin is past its target
  // and its nodes are past half the target from where its boxes were computed, else none (count
  // 0; the margin may stay past its target a tick while slices wait to be measured). The margin
  // then assumes it was refit.
  void next_slice(uint32_t& first, uint32_t& count) noexcept;
  void unbind() noexcept { bound_ = false; }  // every slice takes the body's largest node move
  bool bound() const noexcept { return bound_; }
  double margin() const noexcept { return margin_; }  // m
  // How far any vertex of slice `slice` may be from where its boxes were computed, m.
  double slice_margin(size_t slice) const noexcept {
    return weight_bound_ * (drift_[slice] + pending_);
  }
  double margin_cap() const noexcept { return margin_cap_; }
  // A reading that only grows, for the proxy's patches and free-space check: no vertex has
  // moved further between two instants than odometer() at the second less odometer_base() at
  // the first, m. Every node move the advances and resets read counts, whatever refit followed;
  // NaN once a node was not finite.
  double odometer() const noexcept { return weight_bound_ * (taken_ + pending_); }
  // The largest move of a followed node the last advance read, m (infinite after a reset, NaN
  // for a node not finite): 0 when nothing the surface follows moved since the call before.
  double last_move() const noexcept { return last_move_; }
  double odometer_base() const noexcept { return weight_bound_ * taken_; }
  // The box (lo x, y, z then hi, m) of the vertices of the run [first, first + kSliceElements)
  // of the element order, where the hierarchy's boxes for it were just computed (after reset
  // and bind, or the run's refit): what clearance reads. A reset or bind forgets every box, and
  // next_slice the box of the slice it hands out, so a box not given again is never trusted.
  void set_slice_box(uint32_t first, const std::array<double, 6>& box) noexcept;
  // A lower bound on the distance from point (3, m) to the surface now: the least distance to a
  // slice's box less how far its vertices may have moved since, or `limit` (m) when none is
  // nearer; 0 when not known (unbound, a slice without its box, a node or the point not finite).
  // Local, where the odometer is not: a far slice's moves matter only once they near the point.
  double clearance(const double* point, double limit) const noexcept;

 private:
  static constexpr int kPendingTicks = 8;  // advances between the slices taking their paths
  void update_margin() noexcept;
  void take_paths() noexcept;  // each slice's drift grows by its nodes' longest path; paths restart
  // The largest distance of the slice's nodes from where they were at its last refit, m (the
  // slice's path sum where that is not known).
  double measured_drift(size_t slice) const noexcept;
  void take_reference(size_t slice) noexcept;  // the slice's boxes are computed from last_nodes_
  // The largest move of the nodes the slices follow (every node while unbound) from
  // last_nodes_ to `nodes`, m; NaN for a node not finite.
  double largest_move(const double* nodes) const noexcept;
  std::vector<double> last_nodes_;  // 3 per node, m: at the last advance or reset
  std::vector<double> paths_;       // 1 per node, m: its moves summed since the slices took them
  std::vector<double> drift_;  // per slice, m: its nodes' longest path since refit, less pending_
  std::vector<uint32_t> slice_nodes_;  // the nodes each slice follows, slice after slice
  std::vector<uint32_t> slice_start_;  // per slice + 1: its first entry in slice_nodes_
  std::vector<double> reference_;      // 3 per slice_nodes_ entry, m: where it was at the refit
  std::vector<uint8_t> referenced_;    // per slice: reference_ holds its nodes at its last refit
  std::vector<std::array<double, 6>> slice_boxes_;  // per slice, m: see set_slice_box
  std::vector<uint8_t> boxed_;                      // per slice: slice_boxes_ holds its box
  std::vector<uint32_t> seen_in_;        // 1 per node: the last slice (+ 1) that listed it
  std::vector<uint32_t> surface_nodes_;  // the nodes any slice follows, once each
  bool bound_ = false;
  uint32_t nodes_per_vertex_ = 1;
  uint32_t element_count_ = 0;
  double weight_bound_ = 1.0;
  double margin_target_ = 0.0;
  double margin_cap_ = 0.0;
  double margin_ = 0.0;
  double pending_ = 0.0;  // the longest of paths_, m
  double taken_ = 0.0;    // m: the longest paths taken, summed (pending_ apart)
  double last_move_ = std::numeric_limits<double>::infinity();  // m, see last_move()
  bool read_once_ = false;  // last_nodes_ holds nodes read by a reset or an advance
  int pending_ticks_ = 0;
};

}  // namespace tacta
