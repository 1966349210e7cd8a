// A bounding volume hierarchy over the swept boxes of one surface's elements (triangles or
// tets): built top-down by median split, refit bottom-up in O(n) each tick, rebuilt when the
// refit tree's total node surface area has grown past a ratio of the area right after a build.
// Internal nodes are axis-aligned boxes, or oriented boxes along the principal axes of their
// elements (fixed at build, extents refit); every leaf holds one element and its exact
// axis-aligned swept box, so the candidate pairs are exactly the element pairs whose swept
// boxes overlap, whichever volume the internal nodes use.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tacta::collision {

struct Aabb {
  std::array<double, 3> lo{}, hi{};
  bool overlaps(const Aabb& o) const noexcept {
    return lo[0] <= o.hi[0] && o.lo[0] <= hi[0] && lo[1] <= o.hi[1] && o.lo[1] <= hi[1] &&
           lo[2] <= o.hi[2] && o.lo[2] <= hi[2];
  }
  bool empty() const noexcept { return !(lo[0] <= hi[0] && lo[1] <= hi[1] && lo[2] <= hi[2]); }
};

// An oriented box: center + sum of axes[k] * [-half[k], half[k]]; axis-aligned when axes = I.
struct Obb {
  std::array<double, 3> center{};
  std::array<std::array<double, 3>, 3> axes{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  std::array<double, 3> half{};
};

bool overlaps(const Obb& a, const Obb& b) noexcept;  // separating axis test, 15 axes

struct ElementView {
  const double* start = nullptr;  // 3 per vertex, m
  const double* end = nullptr;    // 3 per vertex, m
  const uint32_t* elements = nullptr;
  uint32_t vertices_per_element = 3;
  uint32_t element_count = 0;
  uint32_t vertex_count = 0;
  double margin = 0.0;  // m, added on every side (contact thickness)
};

class BoundingTree {
 public:
  enum class Volume { kAabb, kObb };

  // Allocates for element_count elements; nothing allocates after this.
  void reserve(uint32_t element_count);
  // Refit or, when quality degraded past rebuild_ratio (or the first time), rebuild.
  // Returns true when rebuilt. Elements with non-finite or out-of-range vertices get an empty
  // box (never reported) and raise bad_elements.
  bool update(const ElementView& view, Volume volume, double rebuild_ratio) noexcept;
  // The elements as the leaves keep them, left to right (valid until the next update).
  const uint32_t* order() const noexcept { return order_.data(); }
  // After a first update: the boxes of the elements order()[first, first + count) from the
  // view's current positions, and every ancestor's from its children (the others keep the boxes
  // they had). For a refit spread over several ticks; never rebuilds. False before an update.
  bool refit_range(const ElementView& view, uint32_t first, uint32_t count) noexcept;

  uint32_t bad_elements() const noexcept { return bad_elements_; }
  uint32_t node_count() const noexcept { return node_count_; }
  uint32_t element_count() const noexcept { return node_count_ == 0 ? 0 : nodes_[0].count; }
  bool built() const noexcept { return built_; }
  const Aabb& element_box(uint32_t element) const noexcept { return element_boxes_[element]; }

  // Calls visit(element_a, element_b) for every element pair of (this, other) whose boxes
  // overlap; self (other == this) reports each unordered pair once with a < b. Returns false
  // if the traversal stack overflowed (pairs may be missing).
  template <class Visit>
  bool pairs(const BoundingTree& other, Visit&& visit) const noexcept;
  // Calls visit(element) for every element whose box overlaps box.
  template <class Visit>
  bool query(const Aabb& box, Visit&& visit) const noexcept;
  // Nearest first: calls visit(element) for the elements whose box, grown by margin (m), may hold
  // a point within `best` (m) of p, nearer subtrees first; visit lowers best as it finds closer
  // ones, which prunes the rest.
  template <class Visit>
  bool nearest(const std::array<double, 3>& p, double margin, double& best,
               Visit&& visit) const noexcept;

 private:
  // One 64-byte cache line: the oriented volumes, only read with Volume::kObb, live apart.
  struct Node {
    Aabb box;                       // axis-aligned bound, kept for every node (cheap first test)
    uint32_t first = 0, count = 0;  // range in order_
    uint32_t left = 0, right = 0;   // children; leaf when count == 1
  };
  bool node_overlap(uint32_t a, const BoundingTree& other, uint32_t b) const noexcept;
  uint32_t build(uint32_t first, uint32_t count, const ElementView& view) noexcept;
  void fit_axes(uint32_t index) noexcept;
  void refit(const ElementView& view) noexcept;
  void refit_node(uint32_t index) noexcept;  // its box (and oriented volume) from its children
  void element_box(const ElementView& view, uint32_t element) noexcept;
  void refit_leaves(uint32_t index, const ElementView& view, uint32_t first, uint32_t end) noexcept;
  double total_area() const noexcept;
  Aabb swept_box(const ElementView& view, uint32_t element, bool& ok) const noexcept;

  Volume volume_ = Volume::kAabb;
  std::vector<Node> nodes_;
  std::vector<Obb> volumes_;  // per node
  std::vector<uint32_t> order_;
  std::vector<Aabb> element_boxes_;
  std::vector<std::array<double, 3>> centroids_;
  uint32_t node_count_ = 0, element_count_ = 0, bad_elements_ = 0;
  double built_area_ = 0.0;
  bool built_ = false;
};

// ---- traversals (templates) ---------------------------------------------------------------------

template <class Visit>
bool BoundingTree::pairs(const BoundingTree& other, Visit&& visit) const noexcept {
  if (node_count_ == 0 || other.node_count_ == 0) return true;
  const bool self = &other == this;
  std::array<std::array<uint32_t, 2>, 1024> stack;
  uint32_t size = 0;
  stack[size++] = {0, 0};
  while (size > 0) {
    const auto [ia, ib] = stack[--size];
    const Node& a = nodes_[ia];
    const Node& b = other.nodes_[ib];
    if (!(self && ia == ib) && !node_overlap(ia, other, ib)) continue;
    const bool leaf_a = a.count == 1, leaf_b = b.count == 1;
    if (leaf_a && leaf_b) {
      if (self && ia == ib) continue;
      const uint32_t ea = order_[a.first], eb = other.order_[b.first];
      if (self) {
        visit(ea < eb ? ea : eb, ea < eb ? eb : ea);
      } else {
        visit(ea, eb);
      }
      continue;
    }
    if (size + 4 > stack.size()) return false;
    if (self && ia == ib) {  // a node against itself: both children with themselves and each other
      stack[size++] = {a.left, a.left};
      stack[size++] = {a.right, a.right};
      stack[size++] = {a.left, a.right};
    } else if (leaf_b || (!leaf_a && a.count >= b.count)) {
      stack[size++] = {a.left, ib};
      stack[size++] = {a.right, ib};
    } else {
      stack[size++] = {ia, b.left};
      stack[size++] = {ia, b.right};
    }
  }
  return true;
}

template <class Visit>
bool BoundingTree::query(const Aabb& box, Visit&& visit) const noexcept {
  if (node_count_ == 0) return true;
  std::array<uint32_t, 256> stack;
  uint32_t size = 0;
  stack[size++] = 0;
  while (size > 0) {
    const Node& n = nodes_[stack[--size]];
    if (!n.box.overlaps(box)) continue;
    if (n.count == 1) {
      const uint32_t e = order_[n.first];
      if (element_boxes_[e].overlaps(box)) visit(e);
      continue;
    }
    if (size + 2 > stack.size()) return false;
    stack[size++] = n.left;
    stack[size++] = n.right;
  }
  return true;
}

// Squared distance (m^2) from p to box; 0 inside.
inline double squared_distance(const Aabb& box, const std::array<double, 3>& p) noexcept {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double below = box.lo[k] - p[k], above = p[k] - box.hi[k];
    const double out = below > 0.0 ? below : (above > 0.0 ? above : 0.0);
    d2 += out * out;
  }
  return d2;
}

template <class Visit>
bool BoundingTree::nearest(const std::array<double, 3>& p, double margin, double& best,
                           Visit&& visit) const noexcept {
  if (node_count_ == 0) return true;
  // Each entry keeps its box's squared distance, measured once when its parent pushed it.
  struct Entry {
    uint32_t node;
    double d2;  // m^2
  };
  std::array<Entry, 256> stack;
  uint32_t size = 0;
  stack[size++] = {0, squared_distance(nodes_[0].box, p)};
  while (size > 0) {
    const Entry top = stack[--size];
    const Node& n = nodes_[top.node];
    const double reach = best + margin;  // a box further than this holds nothing nearer
    if (n.box.empty() || top.d2 > reach * reach) continue;
    if (n.count == 1) {
      visit(order_[n.first]);
      continue;
    }
    if (size + 2 > stack.size()) return false;
    const Entry left{n.left, squared_distance(nodes_[n.left].box, p)};
    const Entry right{n.right, squared_distance(nodes_[n.right].box, p)};
    // The nearer child is popped first.
    stack[size++] = left.d2 <= right.d2 ? right : left;
    stack[size++] = left.d2 <= right.d2 ? left : right;
  }
  return true;
}

}  // namespace tacta::collision
