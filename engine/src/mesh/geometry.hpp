// Small 3D vector helpers for the mesh code (positions are flat arrays of 3 doubles per point).
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace tacta::mesh_detail {

// A point or vector, m. A struct of its own (not std::array) so the operators below are found.
struct P3 {
  double v[3];
  double& operator[](size_t i) { return v[i]; }
  double operator[](size_t i) const { return v[i]; }
};

inline P3 point(const std::vector<double>& positions, uint32_t i) {
  return {positions[3 * size_t{i}], positions[3 * size_t{i} + 1], positions[3 * size_t{i} + 2]};
}
inline P3 operator-(const P3& a, const P3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline P3 operator+(const P3& a, const P3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline P3 operator*(double s, const P3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline double dot(const P3& a, const P3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline P3 cross(const P3& a, const P3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const P3& a) { return std::sqrt(dot(a, a)); }
// a . (b x c): six times the signed volume of the tet (0, a, b, c).
inline double triple(const P3& a, const P3& b, const P3& c) { return dot(a, cross(b, c)); }

// Barycentric weights of p in tet (a, b, c, d); they sum to 1 and reproduce p (also outside).
inline std::array<double, 4> barycentric(const P3& p, const P3& a, const P3& b, const P3& c,
                                         const P3& d) {
  double six_volume = triple(b - a, c - a, d - a);
  double wb = triple(p - a, c - a, d - a) / six_volume;
  double wc = triple(b - a, p - a, d - a) / six_volume;
  double wd = triple(b - a, c - a, p - a) / six_volume;
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
