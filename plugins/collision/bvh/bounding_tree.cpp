#include "bounding_tree.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "tacta/vec3.hpp"

namespace tacta::collision {
namespace {
// `count` copies of `value`, with room for a quarter more: a cut adds a few triangles at a time,
// and an array assigned past its capacity moves to fresh pages at every cut.
template <class T>
void assign_with_room(std::vector<T>& v, size_t count, const T& value) {
  if (count > v.capacity()) {
    v.clear();  // assign overwrites everything: nothing to copy
    v.reserve(count + count / 4);
  }
  v.assign(count, value);
}

constexpr double kInf = std::numeric_limits<double>::infinity();

Aabb empty_box() {
  Aabb b;
  b.lo = {kInf, kInf, kInf};
  b.hi = {-kInf, -kInf, -kInf};
  return b;
}

void grow(Aabb& b, const double* p) {
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = std::min(b.lo[k], p[k]);
    b.hi[k] = std::max(b.hi[k], p[k]);
  }
}

Obb as_obb(const Aabb& b) {
  Obb o;
  for (int k = 0; k < 3; ++k) {
    o.center[k] = 0.5 * (b.lo[k] + b.hi[k]);
    o.half[k] = 0.5 * (b.hi[k] - b.lo[k]);
  }
  return o;
}

double area(const Aabb& b) {
  if (b.empty()) return 0.0;
  const double x = b.hi[0] - b.lo[0], y = b.hi[1] - b.lo[1], z = b.hi[2] - b.lo[2];
  return 2.0 * (x * y + y * z + z * x);
}

}  // namespace

bool overlaps(const Obb& a, const Obb& b) noexcept {
  std::array<double, 3> d{b.center[0] - a.center[0], b.center[1] - a.center[1],
                          b.center[2] - a.center[2]};
  // Projection radius of a box on an axis, then the separating test.
  auto separated = [&](const std::array<double, 3>& axis) {
    const double len2 = dot(axis, axis);
    if (len2 < 1e-24) return false;  // parallel edge pair: that axis is covered by face axes
    double ra = 0.0, rb = 0.0;
    for (int k = 0; k < 3; ++k) {
      ra += a.half[k] * std::abs(dot(a.axes[k], axis));
      rb += b.half[k] * std::abs(dot(b.axes[k], axis));
    }
    // A small relative slack keeps the test conservative under rounding.
    return std::abs(dot(d, axis)) > (ra + rb) * (1.0 + 1e-12) + 1e-300;
  };
  for (int k = 0; k < 3; ++k)
    if (separated(a.axes[k]) || separated(b.axes[k])) return false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const auto& u = a.axes[i];
      const auto& v = b.axes[j];
      if (separated(
              {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]}))
        return false;
    }
  return true;
}

void BoundingTree::reserve(uint32_t element_count) {
  const uint32_t nodes = element_count == 0 ? 0 : 2 * element_count - 1;
  assign_with_room(nodes_, nodes, Node{});
  assign_with_room(volumes_, nodes, Obb{});
  assign_with_room(order_, element_count, uint32_t{0});
  assign_with_room(element_boxes_, element_count, Aabb{});
  assign_with_room(centroids_, element_count, decltype(centroids_)::value_type{});
  element_count_ = element_count;
  node_count_ = 0;
  built_ = false;
}

Aabb BoundingTree::swept_box(const ElementView& view, uint32_t element, bool& ok) const noexcept {
  const uint32_t n = view.vertices_per_element;
  const uint32_t* vertices = view.elements + size_t{n} * element;
  ok = true;
  for (uint32_t i = 0; i < n; ++i)
    if (vertices[i] >= view.vertex_count) {
      ok = false;
      return empty_box();
    }
  Aabb b;
  const double* s0 = view.start + 3 * size_t{vertices[0]};
  const double* e0 = view.end + 3 * size_t{vertices[0]};
  double finite = 0.0;  // 0 * x is NaN for a NaN or infinite x: one test for every coordinate
  for (int k = 0; k < 3; ++k) {
    b.lo[k] = std::min(s0[k], e0[k]);
    b.hi[k] = std::max(s0[k], e0[k]);
    finite += 0.0 * s0[k] + 0.0 * e0[k];
  }
  for (uint32_t i = 1; i < n; ++i) {
    const double* s = view.start + 3 * size_t{vertices[i]};
    const double* e = view.end + 3 * size_t{vertices[i]};
    for (int k = 0; k < 3; ++k) {
      finite += 0.0 * s[k] + 0.0 * e[k];
      b.lo[k] = std::min(b.lo[k], std::min(s[k], e[k]));
      b.hi[k] = std::max(b.hi[k], std::max(s[k], e[k]));
    }
  }
  if (finite != 0.0) {
    ok = false;
    return empty_box();
  }
  for (int k = 0; k < 3; ++k) {
    b.lo[k] -= view.margin;
    b.hi[k] += view.margin;
  }
  return b;
}

bool BoundingTree::node_overlap(uint32_t ia, const BoundingTree& other,
                                uint32_t ib) const noexcept {
  const Node& a = nodes_[ia];
  const Node& b = other.nodes_[ib];
  if (!a.box.overlaps(b.box)) return false;
  if (volume_ == Volume::kAabb || (a.count == 1 && b.count == 1)) return true;
  return overlaps(volumes_[ia], other.volumes_[ib]);
}

void BoundingTree::fit_axes(uint32_t index) noexcept {
  const Node& node = nodes_[index];
  // Principal axes of the element centroids in this node (covariance eigenvectors).
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (uint32_t i = 0; i < node.count; ++i) {
    const auto& c = centroids_[order_[node.first + i]];
    mean += Eigen::Vector3d(c[0], c[1], c[2]);
  }
  mean /= static_cast<double>(node.count);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (uint32_t i = 0; i < node.count; ++i) {
    const auto& c = centroids_[order_[node.first + i]];
    const Eigen::Vector3d d = Eigen::Vector3d(c[0], c[1], c[2]) - mean;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(cov);
  Eigen::Matrix3d axes = solver.eigenvectors();
  if (!axes.allFinite()) axes.setIdentity();
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j) volumes_[index].axes[k][j] = axes(j, k);
}

uint32_t BoundingTree::build(uint32_t first, uint32_t count, const ElementView& view) noexcept {
  const uint32_t index = node_count_++;
  Node& node = nodes_[index];
  node.first = first;
  node.count = count;
  if (count == 1) return index;
  Aabb centre_box = empty_box();
  for (uint32_t i = 0; i < count; ++i) grow(centre_box, centroids_[order_[first + i]].data());
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (centre_box.hi[k] - centre_box.lo[k] > centre_box.hi[axis] - centre_box.lo[axis]) axis = k;
  const uint32_t half = count / 2;
  std::nth_element(
      order_.begin() + first, order_.begin() + first + half, order_.begin() + first + count,
      [&](uint32_t a, uint32_t b) { return centroids_[a][axis] < centroids_[b][axis]; });
  if (volume_ == Volume::kObb) fit_axes(index);
  const uint32_t left = build(first, half, view);
  const uint32_t right = build(first + half, count - half, view);
  nodes_[index].left = left;
  nodes_[index].right = right;
  return index;
}

void BoundingTree::refit(const ElementView& /*view*/) noexcept {
  // Children always have larger indices than their parent (pre-order build): one reverse pass.
  for (uint32_t i = node_count_; i-- > 0;) refit_node(i);
}

void BoundingTree::refit_node(uint32_t index) noexcept {
  Node& n = nodes_[index];
  if (n.count == 1) {
    n.box = element_boxes_[order_[n.first]];
    if (volume_ == Volume::kObb) volumes_[index] = as_obb(n.box);
    return;
  }
  const Node& l = nodes_[n.left];
  const Node& r = nodes_[n.right];
  for (int k = 0; k < 3; ++k) {
    n.box.lo[k] = std::min(l.box.lo[k], r.box.lo[k]);
    n.box.hi[k] = std::max(l.box.hi[k], r.box.hi[k]);
  }
  if (volume_ == Volume::kAabb) return;
  // Extents along the node's fixed axes, from the children's 8 corners each.
  Obb& volume = volumes_[index];
  std::array<double, 3> lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};
  for (const uint32_t c : {n.left, n.right}) {
    if (nodes_[c].box.empty()) continue;
    const Obb& child = volumes_[c];
    for (int corner = 0; corner < 8; ++corner) {
      std::array<double, 3> p = child.center;
      for (int k = 0; k < 3; ++k) {
        const double s = (corner >> k) & 1 ? child.half[k] : -child.half[k];
        for (int j = 0; j < 3; ++j) p[j] += s * child.axes[k][j];
      }
      for (int k = 0; k < 3; ++k) {
        const double q = dot(p, volume.axes[k]);
        lo[k] = std::min(lo[k], q);
        hi[k] = std::max(hi[k], q);
      }
    }
  }
  if (lo[0] > hi[0]) {
    volume = as_obb(n.box);
    return;
  }
  volume.center = {0, 0, 0};
  for (int k = 0; k < 3; ++k) {
    volume.half[k] = 0.5 * (hi[k] - lo[k]);
    for (int j = 0; j < 3; ++j) volume.center[j] += 0.5 * (hi[k] + lo[k]) * volume.axes[k][j];
  }
}

double BoundingTree::total_area() const noexcept {
  double sum = 0.0;
  for (uint32_t i = 0; i < node_count_; ++i)
    if (nodes_[i].count > 1) sum += area(nodes_[i].box);
  return sum;
}

void BoundingTree::element_box(const ElementView& view, uint32_t e) noexcept {
  bool ok = true;
  element_boxes_[e] = swept_box(view, e, ok);
  if (!ok) ++bad_elements_;
  for (int k = 0; k < 3; ++k)
    centroids_[e][k] = ok ? 0.5 * (element_boxes_[e].lo[k] + element_boxes_[e].hi[k]) : 0.0;
}

bool BoundingTree::refit_range(const ElementView& view, uint32_t first, uint32_t count) noexcept {
  bad_elements_ = 0;
  if (!built_ || node_count_ == 0) return false;
  const uint32_t end = std::min(first + count, nodes_[0].count);
  if (first < end) refit_leaves(0, view, first, end);
  return true;
}

// Post-order over the nodes whose leaves meet order_[first, end): a run of leaves is a few whole
// subtrees and the paths above them.
void BoundingTree::refit_leaves(uint32_t index, const ElementView& view, uint32_t first,
                                uint32_t end) noexcept {
  const Node& n = nodes_[index];
  if (n.first >= end || n.first + n.count <= first) return;
  if (n.count == 1) {
    bool ok = true;  // the centroids are for builds, which never happen here
    const uint32_t e = order_[n.first];
    element_boxes_[e] = swept_box(view, e, ok);
    if (!ok) ++bad_elements_;
  } else {
    refit_leaves(n.left, view, first, end);
    refit_leaves(n.right, view, first, end);
  }
  refit_node(index);
}

bool BoundingTree::update(const ElementView& view, Volume volume, double rebuild_ratio) noexcept {
  bad_elements_ = 0;
  const uint32_t n = std::min(view.element_count, element_count_);
  for (uint32_t e = 0; e < n; ++e) element_box(view, e);
  if (n == 0) {
    node_count_ = 0;
    return false;
  }
  bool rebuilt = false;
  if (!built_ || volume != volume_) {
    rebuilt = true;
  } else {
    refit(view);
    rebuilt = total_area() > rebuild_ratio * built_area_;
  }
  if (rebuilt) {
    volume_ = volume;
    node_count_ = 0;
    for (uint32_t e = 0; e < n; ++e) order_[e] = e;
    build(0, n, view);
    refit(view);
    built_area_ = total_area();
    built_ = true;
  }
  return rebuilt;
}

}  // namespace tacta::collision
