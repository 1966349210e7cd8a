#include "collision/proxy_freshness.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tacta {

namespace {
double squared_distance(const double* a, const double* b) noexcept {  // m^2, 3 coordinates each
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}
}  // namespace

SurfaceFreshness::SurfaceFreshness(size_t node_count, uint32_t element_count, double weight_bound,
                                   double margin_target, double margin_cap,
                                   uint32_t nodes_per_vertex)
    : last_nodes_(3 * node_count, 0.0),
      paths_(node_count, 0.0),
      drift_(std::max<size_t>(1, (element_count + kSliceElements - 1) / kSliceElements), 0.0),
      slice_start_(drift_.size() + 1, 0),
      referenced_(drift_.size(), 0),
      slice_boxes_(drift_.size()),
      boxed_(drift_.size(), 0),
      seen_in_(node_count, 0),
      nodes_per_vertex_(nodes_per_vertex),
      element_count_(element_count),
      weight_bound_(weight_bound),
      margin_target_(margin_target),
      margin_cap_(margin_cap) {
  surface_nodes_.reserve(node_count);
  // A slice lists each node once: at most its vertices' nodes, and at most every node.
  const size_t per_slice =
      std::min<size_t>(size_t{3} * kSliceElements * nodes_per_vertex, node_count);
  slice_nodes_.reserve(drift_.size() * per_slice);
  reference_.reserve(3 * slice_nodes_.capacity());
}

void SurfaceFreshness::reset(const double* nodes) noexcept {
  // The boxes start afresh, the odometer does not: the nodes may have moved since the last read.
  if (read_once_) taken_ += pending_ + largest_move(nodes);
  read_once_ = true;
  last_move_ = std::numeric_limits<double>::infinity();
  std::copy(nodes, nodes + last_nodes_.size(), last_nodes_.begin());
  std::fill(drift_.begin(), drift_.end(), 0.0);
  std::fill(paths_.begin(), paths_.end(), 0.0);
  pending_ = 0.0;
  pending_ticks_ = 0;
  margin_ = 0.0;
  for (size_t slice = 0; bound_ && slice < drift_.size(); ++slice) take_reference(slice);
  std::fill(boxed_.begin(), boxed_.end(), uint8_t{0});
}

void SurfaceFreshness::bind(const uint32_t* order, const uint32_t* triangles,
                            const uint32_t* vertex_nodes) noexcept {
  bound_ = false;
  std::fill(boxed_.begin(), boxed_.end(), uint8_t{0});
  slice_nodes_.clear();  // keeps the capacity reserved for every slice's nodes
  std::fill(seen_in_.begin(), seen_in_.end(), 0u);
  for (uint32_t slice = 0; slice < drift_.size(); ++slice) {
    slice_start_[slice] = static_cast<uint32_t>(slice_nodes_.size());
    const uint32_t end = std::min(element_count_, (slice + 1) * kSliceElements);
    for (uint32_t e = slice * kSliceElements; e < end; ++e)
      for (uint32_t c = 0; c < 3; ++c) {
        const uint32_t vertex = triangles[3 * size_t{order[e]} + c];
        for (uint32_t j = 0; j < nodes_per_vertex_; ++j) {
          const uint32_t node =
              vertex_nodes ? vertex_nodes[size_t{nodes_per_vertex_} * vertex + j] : vertex;
          if (node >= seen_in_.size()) return;  // not this body's node: stays unbound
          if (seen_in_[node] == slice + 1) continue;
          seen_in_[node] = slice + 1;
          slice_nodes_.push_back(node);  // within the capacity reserved: no allocation
        }
      }
  }
  slice_start_[drift_.size()] = static_cast<uint32_t>(slice_nodes_.size());
  surface_nodes_.clear();
  for (uint32_t node = 0; node < seen_in_.size(); ++node)
    if (seen_in_[node] != 0) surface_nodes_.push_back(node);
  reference_.resize(3 * slice_nodes_.size());  // within the capacity reserved
  bound_ = true;
  // Right after reset, last_nodes_ is where every box was computed; later, not known until the
  // slice's next refit.
  for (size_t slice = 0; slice < drift_.size(); ++slice)
    if (drift_[slice] == 0.0 && pending_ == 0.0)
      take_reference(slice);
    else
      referenced_[slice] = 0;
}

void SurfaceFreshness::take_reference(size_t slice) noexcept {
  for (uint32_t k = slice_start_[slice]; k < slice_start_[slice + 1]; ++k) {
    const double* now = &last_nodes_[3 * size_t{slice_nodes_[k]}];
    std::copy(now, now + 3, &reference_[3 * size_t{k}]);
  }
  referenced_[slice] = 1;
}

double SurfaceFreshness::largest_move(const double* nodes) const noexcept {
  double largest2 = 0.0;  // m^2
  const auto take = [&](size_t i) {
    const double d2 = squared_distance(nodes + i, &last_nodes_[i]);
    largest2 = std::isnan(d2) ? d2 : std::max(largest2, d2);
  };
  if (bound_) {
    for (const uint32_t node : surface_nodes_) take(3 * size_t{node});
  } else {
    for (size_t i = 0; i < last_nodes_.size(); i += 3) take(i);
  }
  return std::sqrt(largest2);
}

double SurfaceFreshness::measured_drift(size_t slice) const noexcept {
  if (!bound_ || !referenced_[slice]) return drift_[slice] + pending_;
  double largest2 = 0.0;  // m^2
  for (uint32_t k = slice_start_[slice]; k < slice_start_[slice + 1]; ++k) {
    largest2 = std::max(largest2, squared_distance(&last_nodes_[3 * size_t{slice_nodes_[k]}],
                                                   &reference_[3 * size_t{k}]));
  }
  // Never above the path sum, which bounds it too (rounding aside).
  return std::min(drift_[slice] + pending_, std::sqrt(largest2));
}

bool SurfaceFreshness::advance(const double* nodes) noexcept {
  if (!bound_) {
    const double move = largest_move(nodes);  // NaN fails the cap below
    last_move_ = move;
    std::copy(nodes, nodes + last_nodes_.size(), last_nodes_.begin());
    for (double& d : drift_) d += move;
    taken_ += move;
    read_once_ = true;
    update_margin();
    return margin_ <= margin_cap_;
  }
  // Only the nodes some slice follows: the others (a body's inside) move no vertex. Each adds
  // its move to its own path; the slices take their nodes' largest path now and then.
  double finite = 0.0;  // 0 * x is NaN for a NaN or infinite x
  double largest = 0.0;
  for (const uint32_t node : surface_nodes_) {
    double* last = &last_nodes_[3 * size_t{node}];
    const double* now = nodes + 3 * size_t{node};
    const double move = std::sqrt(squared_distance(now, last));
    const double path = paths_[node] + move;
    std::copy(now, now + 3, last);
    paths_[node] = path;
    finite += 0.0 * path;
    largest = std::max(largest, move);
    pending_ = std::max(pending_, path);
  }
  last_move_ = std::isnan(finite) ? finite : largest;
  if (std::isnan(finite)) {
    margin_ = finite;
    return false;
  }
  ++pending_ticks_;
  // A quarter of the target keeps the slices' share of the margin within reach of refits.
  if (pending_ticks_ >= kPendingTicks || weight_bound_ * pending_ > 0.25 * margin_target_)
    take_paths();
  update_margin();
  return margin_ <= margin_cap_;
}

void SurfaceFreshness::take_paths() noexcept {
  for (size_t slice = 0; slice < drift_.size(); ++slice) {
    double longest = 0.0;
    for (uint32_t k = slice_start_[slice]; k < slice_start_[slice + 1]; ++k)
      longest = std::max(longest, paths_[slice_nodes_[k]]);
    drift_[slice] += longest;
  }
  taken_ += pending_;
  for (const uint32_t node : surface_nodes_) paths_[node] = 0.0;
  pending_ = 0.0;
  pending_ticks_ = 0;
}

void SurfaceFreshness::next_slice(uint32_t& first, uint32_t& count) noexcept {
  first = count = 0;
  // A slice measured near its boxes takes that drift; one past half the target is refit. At
  // most kMeasuredPerCall are kept a call (a settling body has every slice cross on one tick):
  // the rest wait a tick with the margin past its target, which the queries widen by.
  constexpr int kMeasuredPerCall = 8;
  for (int kept = 0; margin_ > margin_target_ && kept < kMeasuredPerCall; ++kept) {
    const auto stalest =
        static_cast<uint32_t>(std::max_element(drift_.begin(), drift_.end()) - drift_.begin());
    const double measured = measured_drift(stalest);
    if (weight_bound_ * measured <= 0.5 * margin_target_) {
      drift_[stalest] = measured;  // still near its boxes: no refit
      update_margin();
      continue;
    }
    first = std::min(stalest * kSliceElements, element_count_);
    count = std::min(kSliceElements, element_count_ - first);
    drift_[stalest] = 0.0;
    boxed_[stalest] = 0;  // until the caller gives the refit slice its box
    if (bound_) take_reference(stalest);
    update_margin();
    return;
  }
}

void SurfaceFreshness::update_margin() noexcept {
  margin_ = weight_bound_ * (*std::max_element(drift_.begin(), drift_.end()) + pending_);
}

void SurfaceFreshness::set_slice_box(uint32_t first, const std::array<double, 6>& box) noexcept {
  const size_t slice = first / kSliceElements;
  if (slice >= slice_boxes_.size()) return;
  slice_boxes_[slice] = box;
  boxed_[slice] = 1;
}

double SurfaceFreshness::clearance(const double* point, double limit) const noexcept {
  if (!bound_ || !(margin_ >= 0.0) || !(limit > 0.0) ||
      !(std::isfinite(point[0]) && std::isfinite(point[1]) && std::isfinite(point[2])))
    return 0.0;
  double best = limit;
  for (size_t slice = 0; slice < slice_boxes_.size(); ++slice) {
    const double margin = slice_margin(slice);
    if (!boxed_[slice] || !(margin >= 0.0 && margin < std::numeric_limits<double>::infinity()))
      return 0.0;
    const std::array<double, 6>& box = slice_boxes_[slice];
    double d2 = 0.0;  // m^2, 0 inside
    for (int a = 0; a < 3; ++a) {
      const double out = std::max({box[a] - point[a], point[a] - box[a + 3], 0.0});
      d2 += out * out;
    }
    const double reach = best + margin;  // a box further than this leaves best as it is
    if (!(d2 < reach * reach)) continue;
    best = std::sqrt(d2) - margin;
    if (!(best > 0.0)) return 0.0;
  }
  return best;
}

}  // namespace tacta
