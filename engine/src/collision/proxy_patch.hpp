// The haptic proxy's patch of one collision surface: the triangles near the tool, gathered now and
// then from the hierarchy (the proxy plugin's overlap_shape over a cube, widened by the margin),
// which the proxy's queries then test one by one (TACTA_COLLISION_PROXY_TAKES_CANDIDATES) instead
// of searching the hierarchy. A triangle left out lay outside the cube when it was gathered; none
// of its vertices has moved further than the surface's odometer has advanced since
// (SurfaceFreshness), so a query whose box lies inside the cube shrunk by that cannot reach it.
// Only the patch's vertices need be current. Fixed capacity: no allocation after construction.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

namespace tacta {

class ProxyPatch {
 public:
  // Triangles a patch holds at most: a gather finding more is not kept (those queries search the
  // hierarchy), as testing them one by one would cost more than the search.
  static constexpr uint32_t kCapacity = 96;
  using Box = std::array<double, 6>;  // lo x, y, z then hi x, y, z; m

  ProxyPatch() {
    triangles_.reserve(kCapacity);
    boxes_.reserve(kCapacity);
  }

  // A query over `box` finds every triangle within its reach among triangles(): the box lies
  // inside the gathered cube shrunk on every side by how far the surface's odometer (m) has
  // advanced since the gather (false for a NaN).
  bool covers(const Box& box, double odometer) const noexcept {
    const double travel = odometer - odometer_base_;
    if (!held_ || !(travel >= 0.0)) return false;
    const double half = half_ - travel;
    for (int a = 0; a < 3; ++a)
      if (!(box[a] >= center_[a] - half && box[a + 3] <= center_[a] + half)) return false;
    return true;
  }
  // A query over `box` was answered from the patch: the next gather's cube holds such boxes too.
  // `pass`: the proxy pass it was served in.
  void note_served(const Box& box, uint64_t pass = 0) noexcept {
    for (int a = 0; a < 3; ++a) served_extent_ = std::max(served_extent_, box[a + 3] - box[a]);
    last_served_ = box;
    served_in_ = pass;
  }
  // The proxy pass of the last query the patch (or one gathered before it) served, and that
  // query's box: the upkeep prepares the patches in use for the next tick's queries.
  uint64_t served_in() const noexcept { return served_in_; }
  const Box& last_served() const noexcept { return last_served_; }
  // The cube to gather for a query over `box`, m: centred on it, of half size the largest query
  // side the patch served or this one's (so the tick's other queries fit too, and the tool may
  // move about half a query before the next gather). `alone`: this query's side only.
  void cube_for(const Box& box, bool alone, std::array<double, 3>& center,
                double& half) const noexcept {
    double side = 0.0;
    for (int a = 0; a < 3; ++a) {
      center[a] = 0.5 * (box[a] + box[a + 3]);
      side = std::max(side, box[a + 3] - box[a]);
    }
    half = alone ? side : std::max(side, served_extent_);
  }
  // A gather for a query over `box` is worth trying in proxy pass `pass` (two passes a tick: the
  // haptic stage's and the upkeep's): none for a query of 3/4 the side or more (about half the
  // area) held too many in the last kRetryPasses passes (the god-object's search for a surface
  // that came onto a device well clear of it: a large ball each tick, which the hierarchy
  // answers), twice as many after each further failure in a row, up to 16 times (a failed
  // gather of a few hundred triangles costs tens of us, and a large query that failed twice
  // tends to go on failing while the tool stays clear). Any, once a gather of the size that
  // failed has fit since (the cube served failing, the query's own fitting).
  bool worth_gathering(const Box& box, uint64_t pass) const noexcept {
    if (failures_ == 0) return true;
    const uint32_t doublings = failures_ - 1;  // at most kMaxDoublings
    if (pass - failed_pass_ >= (kRetryPasses << doublings)) return true;
    for (int a = 0; a < 3; ++a)
      if (box[a + 3] - box[a] < 0.75 * failed_side_) return true;
    return false;
  }
  // The cube for the queries served is larger than the one for `box` alone.
  bool widens(const Box& box) const noexcept {
    for (int a = 0; a < 3; ++a)
      if (box[a + 3] - box[a] >= served_extent_) return false;
    return true;
  }
  // The triangles a gather over the cube found for a query over `box` in pass `pass`, with the
  // surface's odometer_base then: kept when they fit (false: the patch is as it was).
  bool keep(const std::array<double, 3>& center, double half, const uint32_t* triangles,
            uint32_t count, const Box& box, uint64_t pass, double odometer_base) noexcept {
    double side = 0.0;
    for (int a = 0; a < 3; ++a) side = std::max(side, box[a + 3] - box[a]);
    if (count > kCapacity) {
      // One failure a pass: a query gathered for the cube served and then alone fails twice.
      const bool similar = failed_side_ <= 1.5 * side && side <= 1.5 * failed_side_;
      if (!similar)
        failures_ = 1;
      else if (pass != failed_pass_ || failures_ == 0)
        failures_ = std::min(failures_ + 1, kMaxDoublings + 1);
      failed_pass_ = pass;
      failed_side_ = side;
      return false;
    }
    if (side >= 0.75 * failed_side_) failures_ = 0;   // one of the size that failed, or larger
    triangles_.assign(triangles, triangles + count);  // within the capacity reserved
    center_ = center;
    half_ = half;
    odometer_base_ = odometer_base;
    held_ = true;
    near_valid_ = false;
    served_extent_ = 0.0;
    made_current_in_ = boxes_in_ = 0;
    return true;
  }
  // The surface changed (a cut, a replacement) or is away: what failed on it says nothing now.
  void drop() noexcept {
    held_ = false;
    near_valid_ = false;
    made_current_in_ = boxes_in_ = served_in_ = 0;
    failures_ = 0;
    failed_side_ = kNoFailedSide;
  }
  bool held() const noexcept { return held_; }
  const uint32_t* triangles() const noexcept { return triangles_.data(); }
  uint32_t count() const noexcept { return static_cast<uint32_t>(triangles_.size()); }
  // The proxy pass in which the patch's vertices were last made current (0: never).
  uint64_t made_current_in() const noexcept { return made_current_in_; }
  void set_made_current_in(uint64_t pass) noexcept { made_current_in_ = pass; }
  // The triangles' boxes, from the surface's positions (3 per vertex, m) and triangles (3 vertex
  // indices each), as of proxy pass `pass`: a pass's queries then test only the triangles whose
  // box meets theirs (meeting), without reading every candidate's corners each query.
  void set_boxes(const double* positions, const uint32_t* surface_triangles,
                 uint64_t pass) noexcept {
    boxes_.clear();  // within the capacity reserved
    near_valid_ = false;
    for (const uint32_t t : triangles_) {
      Box b;
      const double* x = &positions[3 * size_t{surface_triangles[3 * size_t{t}]}];
      for (int a = 0; a < 3; ++a) b[a] = b[a + 3] = x[a];
      for (size_t c = 1; c < 3; ++c) {
        x = &positions[3 * size_t{surface_triangles[3 * size_t{t} + c]}];
        for (int a = 0; a < 3; ++a) {
          b[a] = std::min(b[a], x[a]);
          b[a + 3] = std::max(b[a + 3], x[a]);
        }
      }
      boxes_.push_back(b);
    }
    boxes_in_ = pass;
  }
  uint64_t boxes_in() const noexcept { return boxes_in_; }
  void set_boxes_in(uint64_t pass) noexcept { boxes_in_ = pass; }  // nothing moved since
  // The triangles whose box meets `box` (closed intervals; the boxes are the bvh plugin's own
  // candidate test's, NaN corners included) into out (kCapacity); returns how many, in the
  // patch's order. Those left out lie wholly outside the query's reach, which `box` bounds. The
  // boxes are tested once against a query grown by kNearShare of its side, and the queries after
  // it that lie inside that (the proxy's iterations, micrometres apart) test only those that met
  // it, until the boxes change or a query falls outside.
  uint32_t meeting(const Box& box, uint32_t* out) noexcept {
    bool inside = near_valid_;
    for (int a = 0; a < 3; ++a)
      inside = inside && box[a] >= near_box_[a] && box[a + 3] <= near_box_[a + 3];
    if (!inside) {  // (a NaN box too: every box then meets it, as it meets the query)
      double side = 0.0;
      for (int a = 0; a < 3; ++a) side = std::max(side, box[a + 3] - box[a]);
      for (int a = 0; a < 3; ++a) {
        near_box_[a] = box[a] - kNearShare * side;
        near_box_[a + 3] = box[a + 3] + kNearShare * side;
      }
      near_count_ = 0;
      for (uint32_t i = 0; i < boxes_.size(); ++i) {
        near_[near_count_] = static_cast<uint8_t>(i);
        near_count_ += meets(boxes_[i], near_box_) ? 1u : 0u;
      }
      near_valid_ = true;
    }
    uint32_t count = 0;
    for (uint32_t k = 0; k < near_count_; ++k) {
      out[count] = triangles_[near_[k]];
      count += meets(boxes_[near_[k]], box) ? 1u : 0u;
    }
    return count;
  }

 private:
  static_assert(kCapacity <= 256, "near_ holds box indices in a byte");
  static constexpr uint64_t kRetryPasses = 64;
  static constexpr double kNearShare = 0.25;  // see meeting
  // Closed intervals, without branches (most boxes of a patch are apart from a query's, at random).
  static bool meets(const Box& b, const Box& box) noexcept {
    return !(b[0] > box[3]) & !(b[3] < box[0]) & !(b[1] > box[4]) & !(b[4] < box[1]) &
           !(b[2] > box[5]) & !(b[5] < box[2]);
  }
  static constexpr uint32_t kMaxDoublings = 4;    // retries at least every 1,024 passes
  static constexpr double kNoFailedSide = 1e300;  // m: no gather failed (since the surface changed)
  std::vector<uint32_t> triangles_;
  uint64_t failed_pass_ = 0;  // the last pass a gather held too many triangles, and the query's
  double failed_side_ = kNoFailedSide;  // largest side then, m
  uint32_t failures_ = 0;               // failed gathers in a row for queries of about that side
  std::array<double, 3> center_{};
  double half_ = 0.0;           // m, of the cube gathered over
  double odometer_base_ = 0.0;  // m, the surface's at the gather
  double served_extent_ = 0.0;  // m: the largest side of a query box served since the gather
  uint64_t made_current_in_ = 0;
  std::vector<Box> boxes_;  // of triangles_, as of pass boxes_in_
  uint64_t boxes_in_ = 0;
  // The boxes (indices, kCapacity < 256) meeting near_box_, a query's grown, until the boxes change.
  std::array<uint8_t, kCapacity> near_{};
  uint32_t near_count_ = 0;
  Box near_box_{};
  bool near_valid_ = false;
  Box last_served_{};
  uint64_t served_in_ = 0;
  bool held_ = false;
};

}  // namespace tacta
