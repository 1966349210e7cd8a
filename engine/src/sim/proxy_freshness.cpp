#include "proxy_freshness.hpp"

#include <algorithm>
#include <cmath>

namespace tacta {

namespace {

// Interleaves the low 10 bits of x, y, z (a 30-bit Morton code).
uint32_t morton(uint32_t x, uint32_t y, uint32_t z) noexcept {
  const auto spread = [](uint32_t v) {
    v &= 0x3ffu;
    v = (v | (v << 16)) & 0x030000ffu;
    v = (v | (v << 8)) & 0x0300f00fu;
    v = (v | (v << 4)) & 0x030c30c3u;
    v = (v | (v << 2)) & 0x09249249u;
    return v;
  };
  return spread(x) | (spread(y) << 1) | (spread(z) << 2);
}

}  // namespace

SurfaceFreshness::SurfaceFreshness(size_t node_count, const uint32_t* triangles,
                                   uint32_t triangle_count, const double* positions,
                                   double weight_bound, double margin_cap)
    : last_nodes_(3 * node_count, 0.0),
      // An element refit k ticks ago has moved by the sum of the last k moves: keep a round's.
      moves_((triangle_count + kSliceElements - 1) / kSliceElements + 1, 0.0),
      order_(triangle_count),
      weight_bound_(weight_bound),
      margin_cap_(margin_cap) {
  std::vector<double> centroids(3 * size_t{triangle_count});
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (size_t t = 0; t < triangle_count; ++t)
    for (size_t a = 0; a < 3; ++a) {
      double c = 0;
      for (size_t k = 0; k < 3; ++k) c += positions[3 * size_t{triangles[3 * t + k]} + a] / 3.0;
      centroids[3 * t + a] = std::isfinite(c) ? c : 0.0;
      lo[a] = std::min(lo[a], centroids[3 * t + a]);
      hi[a] = std::max(hi[a], centroids[3 * t + a]);
    }
  std::vector<uint32_t> codes(triangle_count);
  for (size_t t = 0; t < triangle_count; ++t) {
    uint32_t q[3];
    for (size_t a = 0; a < 3; ++a) {
      const double span = hi[a] - lo[a];
      q[a] = span > 0 ? static_cast<uint32_t>(1023.0 * (centroids[3 * t + a] - lo[a]) / span) : 0;
    }
    codes[t] = morton(q[0], q[1], q[2]);
    order_[t] = static_cast<uint32_t>(t);
  }
  std::stable_sort(order_.begin(), order_.end(),
                   [&](uint32_t a, uint32_t b) { return codes[a] < codes[b]; });
}

void SurfaceFreshness::reset(const double* nodes) noexcept {
  std::copy(nodes, nodes + last_nodes_.size(), last_nodes_.begin());
  std::fill(moves_.begin(), moves_.end(), 0.0);
  margin_ = 0.0;
}

bool SurfaceFreshness::advance(const double* nodes) noexcept {
  double largest2 = 0.0;  // m^2
  for (size_t i = 0; i < last_nodes_.size(); i += 3) {
    const double dx = nodes[i] - last_nodes_[i], dy = nodes[i + 1] - last_nodes_[i + 1],
                 dz = nodes[i + 2] - last_nodes_[i + 2];
    // NaN compares false: a non-finite node makes the margin NaN, which fails the cap below.
    const double d2 = dx * dx + dy * dy + dz * dz;
    largest2 = std::isnan(d2) ? d2 : std::max(largest2, d2);
  }
  std::copy(nodes, nodes + last_nodes_.size(), last_nodes_.begin());
  moves_[next_move_] = std::sqrt(largest2);
  next_move_ = (next_move_ + 1) % moves_.size();
  double sum = 0.0;
  for (const double m : moves_) sum += m;
  margin_ = weight_bound_ * sum;
  return margin_ <= margin_cap_;
}

const uint32_t* SurfaceFreshness::next_slice(uint32_t& count) noexcept {
  const auto total = static_cast<uint32_t>(order_.size());
  const uint32_t first = std::min(next_first_, total);
  count = std::min(kSliceElements, total - first);
  next_first_ = first + count >= total ? 0 : first + count;
  return order_.data() + first;
}

}  // namespace tacta
