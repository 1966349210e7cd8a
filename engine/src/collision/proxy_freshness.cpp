#include "collision/proxy_freshness.hpp"

#include <algorithm>
#include <cmath>

namespace tacta {

SurfaceFreshness::SurfaceFreshness(size_t node_count, uint32_t element_count, double weight_bound,
                                   double margin_target, double margin_cap)
    : last_nodes_(3 * node_count, 0.0),
      drift_(std::max<size_t>(1, (element_count + kSliceElements - 1) / kSliceElements), 0.0),
      element_count_(element_count),
      weight_bound_(weight_bound),
      margin_target_(margin_target),
      margin_cap_(margin_cap) {}

void SurfaceFreshness::reset(const double* nodes) noexcept {
  std::copy(nodes, nodes + last_nodes_.size(), last_nodes_.begin());
  std::fill(drift_.begin(), drift_.end(), 0.0);
  margin_ = 0.0;
}

bool SurfaceFreshness::advance(const double* nodes) noexcept {
  double largest2 = 0.0;  // m^2
  for (size_t i = 0; i < last_nodes_.size(); i += 3) {
    const double dx = nodes[i] - last_nodes_[i], dy = nodes[i + 1] - last_nodes_[i + 1],
                 dz = nodes[i + 2] - last_nodes_[i + 2];
    // A non-finite node makes the margin NaN, which fails the cap below.
    const double d2 = dx * dx + dy * dy + dz * dz;
    largest2 = std::isnan(d2) ? d2 : std::max(largest2, d2);
  }
  std::copy(nodes, nodes + last_nodes_.size(), last_nodes_.begin());
  const double move = std::sqrt(largest2);
  for (double& d : drift_) d += move;
  update_margin();
  return margin_ <= margin_cap_;
}

void SurfaceFreshness::next_slice(uint32_t& first, uint32_t& count) noexcept {
  first = count = 0;
  if (!(margin_ > margin_target_)) return;
  const auto stalest =
      static_cast<uint32_t>(std::max_element(drift_.begin(), drift_.end()) - drift_.begin());
  first = std::min(stalest * kSliceElements, element_count_);
  count = std::min(kSliceElements, element_count_ - first);
  drift_[stalest] = 0.0;
  update_margin();
}

void SurfaceFreshness::update_margin() noexcept {
  margin_ = weight_bound_ * *std::max_element(drift_.begin(), drift_.end());
}

}  // namespace tacta
