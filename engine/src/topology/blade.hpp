// The geometric tests a cut makes between the blade's triangles and a deformed tet mesh. Units:
// metres. Tolerances are relative (1e-12 of the tet's size): a blade that only touches a face,
// an edge or a node to round-off does not cut.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "tacta/vec3.hpp"

namespace tacta::topology_detail {

struct Box {
  Vec3 lo, hi;
  bool meets(const Box& other, double pad) const noexcept;
  void include(const Vec3& p) noexcept;
  static Box empty() noexcept;
};

struct BladeTriangle {
  Vec3 a, b, c;
  Box box;
};

// The blade triangles that can cut: finite corners and an area above round-off (a triangle
// flattened to a segment or a point cuts nothing, in either mode). 9 doubles per triangle in.
std::vector<BladeTriangle> cutting_triangles(std::span<const double> triangles);

// True when the closed triangle meets the open interior of the tet x[0..3] (either orientation)
// by more than round-off: no plane among the separating-axis candidates (the tet's face normals,
// the triangle's normal, the cross products of their edges) has the two on opposite sides.
bool triangle_meets_tet_interior(const BladeTriangle& triangle, const std::array<Vec3, 4>& x);

// True when the segment p-q passes through the closed triangle from one side of its plane to the
// other. A point on the plane counts as behind it (the side the normal (b-a) x (c-a) points away
// from), so a segment ending on the plane crosses it from one side only; a segment through an
// edge or a corner crosses every triangle that holds it.
bool segment_crosses_triangle(const Vec3& p, const Vec3& q, const BladeTriangle& triangle);

}  // namespace tacta::topology_detail
