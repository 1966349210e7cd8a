// Mesh helpers over tacta::Vec3 (positions are flat arrays of 3 doubles per point).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tacta/vec3.hpp"

namespace tacta::mesh_detail {

// Point i of a flat position array (3 doubles per point, m).
inline Vec3 point(const std::vector<double>& positions, uint32_t i) {
  return point_at(positions.data(), i);
}

// |6 V| below this times (longest edge)^3 is a flat tet, |2 A| below it times (longest edge)^2 a
// flat planar element (finalize refuses them; a cut's checks use the same bound).
inline constexpr double kFlatVolume = 1e-12;
// A barycentric weight above this still counts as inside (round-off), at binding and after a cut.
inline constexpr double kInsideWeight = -1e-9;

// Barycentric weights of p in tet (a, b, c, d); they sum to 1 and reproduce p (also outside).
inline std::array<double, 4> barycentric(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                                         const Vec3& d) {
  double six_volume = triple(sub(b, a), sub(c, a), sub(d, a));
  double wb = triple(sub(p, a), sub(c, a), sub(d, a)) / six_volume;
  double wc = triple(sub(b, a), sub(p, a), sub(d, a)) / six_volume;
  double wd = triple(sub(b, a), sub(c, a), sub(p, a)) / six_volume;
  return {1.0 - wb - wc - wd, wb, wc, wd};
}

// Elements joined through shared nodes: union-find over node indices (path halving).
class NodeUnion {
 public:
  explicit NodeUnion(size_t nodes) : parent_(nodes) {
    for (uint32_t i = 0; i < parent_.size(); ++i) parent_[i] = i;
  }
  uint32_t root(uint32_t v) {
    while (parent_[v] != v) v = parent_[v] = parent_[parent_[v]];
    return v;
  }
  // Joins the `per` nodes of every element of a flat index array (tets: 4, triangles: 3).
  void join_elements(const std::vector<uint32_t>& elements, size_t per) {
    for (size_t e = 0; e + per <= elements.size(); e += per)
      for (size_t k = 1; k < per; ++k) parent_[root(elements[e + k])] = root(elements[e]);
  }

 private:
  std::vector<uint32_t> parent_;
};

}  // namespace tacta::mesh_detail
