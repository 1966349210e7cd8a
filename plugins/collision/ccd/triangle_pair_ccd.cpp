#include "triangle_pair_ccd.hpp"

#include <algorithm>
#include <cmath>

#include "plain_ccd.hpp"
#include "tacta/vec3.hpp"

namespace tacta::collision {
namespace {

void load(const tacta_collision_surface& s, uint32_t vertex, double* start, double* end) {
  for (int k = 0; k < 3; ++k) {
    start[k] = s.positions_start[3 * vertex + k];
    end[k] = s.positions_end[3 * vertex + k];
  }
}

// Unit normal of the triangle (x0, x1, x2) given as 9 doubles; zero when degenerate.
void unit_normal(const double* x, double* n) {
  const double a[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]};
  const double b[3] = {x[6] - x[0], x[7] - x[1], x[8] - x[2]};
  const Vec3 c = cross(a, b);
  const double length = norm(c);
  for (int k = 0; k < 3; ++k) n[k] = length > 0.0 ? c[k] / length : 0.0;
}

CcdResult run(bool vertex_face, const double* q, CcdMethod method, const CcdTolerance& tol) {
  if (method == CcdMethod::kPlain) return vertex_face ? vertex_face_plain(q) : edge_edge_plain(q);
  return vertex_face ? vertex_face_inclusion(q, tol) : edge_edge_inclusion(q, tol);
}

// Fills the geometric part of a contact from the 4 points at time toi: the point on b, the
// normal from b towards a and the depth (thickness minus end-of-tick gap along the normal).
void finish(tacta_contact& c, const double* q, double thickness) {
  double x[12];
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      const double s = q[3 * i + k], e = q[3 * (i + 4) + k];
      x[3 * i + k] = s + c.toi * (e - s);
    }
  double point_a[3], point_b[3], n[3];
  for (int k = 0; k < 3; ++k) {
    point_a[k] = c.weights_a[0] * x[k] + c.weights_a[1] * x[3 + k] + c.weights_a[2] * x[6 + k];
    point_b[k] = c.weights_b[0] * x[3 + k] + c.weights_b[1] * x[6 + k] + c.weights_b[2] * x[9 + k];
  }
  if (c.type == TACTA_CONTACT_VERTEX_FACE) {
    unit_normal(x + 3, n);
  } else {
    const double ea[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]};
    const double eb[3] = {x[9] - x[6], x[10] - x[7], x[11] - x[8]};
    const Vec3 normal = cross(ea, eb);
    for (int k = 0; k < 3; ++k) n[k] = normal[k];
    double length = norm(n);
    const double scale = std::sqrt(dot(ea, ea) * dot(eb, eb));
    // Nearly parallel edges (under ~0.06 degrees): the cross product's direction is rounding
    // noise; use the separation of the two contact points at the start of the tick instead.
    if (!(length > 1e-3 * scale)) {
      for (int k = 0; k < 3; ++k)
        n[k] = c.weights_a[0] * q[k] + c.weights_a[1] * q[3 + k] + c.weights_a[2] * q[6 + k] -
               (c.weights_b[0] * q[3 + k] + c.weights_b[1] * q[6 + k] + c.weights_b[2] * q[9 + k]);
      length = norm(n);
    }
    for (int k = 0; k < 3; ++k) n[k] = length > 0.0 ? n[k] / length : 0.0;
  }
  // Orient the normal by the side a was on at the start of the tick.
  double side = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double sa = c.weights_a[0] * q[k] + c.weights_a[1] * q[3 + k] + c.weights_a[2] * q[6 + k];
    const double sb =
        c.weights_b[0] * q[3 + k] + c.weights_b[1] * q[6 + k] + c.weights_b[2] * q[9 + k];
    side += (sa - sb) * n[k];
  }
  if (side < 0.0)
    for (double& v : n) v = -v;
  double gap = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double ea =
        c.weights_a[0] * q[12 + k] + c.weights_a[1] * q[15 + k] + c.weights_a[2] * q[18 + k];
    const double eb =
        c.weights_b[0] * q[15 + k] + c.weights_b[1] * q[18 + k] + c.weights_b[2] * q[21 + k];
    gap += (ea - eb) * n[k];
  }
  for (int k = 0; k < 3; ++k) {
    c.point[k] = point_b[k];
    c.normal[k] = n[k];
    c.force[k] = 0.0;
  }
  (void)point_a;
  c.depth = thickness - gap;
}

}  // namespace

uint32_t triangle_pair_contacts(const tacta_collision_world& world, TriangleRef a, TriangleRef b,
                                CcdMethod method, const CcdTolerance& tolerance,
                                tacta_contact* contacts, uint32_t capacity,
                                uint32_t& count) noexcept {
  if (a.surface >= world.surface_count || b.surface >= world.surface_count)
    return TACTA_COLLIDE_DEGENERATE;
  const tacta_collision_surface& sa = world.surfaces[a.surface];
  const tacta_collision_surface& sb = world.surfaces[b.surface];
  if (a.triangle >= sa.triangle_count || b.triangle >= sb.triangle_count)
    return TACTA_COLLIDE_DEGENERATE;
  const uint32_t* ta = sa.triangles + 3 * a.triangle;
  const uint32_t* tb = sb.triangles + 3 * b.triangle;
  for (int i = 0; i < 3; ++i)
    if (ta[i] >= sa.vertex_count || tb[i] >= sb.vertex_count) return TACTA_COLLIDE_DEGENERATE;
  const bool same = a.surface == b.surface;
  const double thickness = std::max(sa.thickness, sb.thickness);
  uint32_t bits = 0;
  double q[24];
  // Vertex-face both ways: (vertex of first, triangle of second).
  for (int direction = 0; direction < 2; ++direction) {
    const tacta_collision_surface& sv = direction == 0 ? sa : sb;
    const tacta_collision_surface& sf = direction == 0 ? sb : sa;
    const uint32_t* tv = direction == 0 ? ta : tb;
    const uint32_t* tf = direction == 0 ? tb : ta;
    const TriangleRef rv = direction == 0 ? a : b, rf = direction == 0 ? b : a;
    for (int i = 0; i < 3; ++i) {
      if (same && (tv[i] == tf[0] || tv[i] == tf[1] || tv[i] == tf[2])) continue;
      load(sv, tv[i], q, q + 12);
      for (int j = 0; j < 3; ++j) load(sf, tf[j], q + 3 + 3 * j, q + 15 + 3 * j);
      const CcdResult r = run(true, q, method, tolerance);
      if (r.not_finite) bits |= TACTA_COLLIDE_NOT_FINITE;
      if (!r.hit) continue;
      if (count >= capacity) return bits | TACTA_COLLIDE_OVERFLOW;
      tacta_contact& c = contacts[count++];
      c = tacta_contact{};
      c.type = TACTA_CONTACT_VERTEX_FACE;
      c.index_a = rv.surface;
      c.index_b = rf.surface;
      c.body_a = sv.body_id;
      c.body_b = sf.body_id;
      c.feature_a = tv[i];
      c.feature_b = rf.triangle;
      c.nodes_a[0] = tv[i];
      c.nodes_a[1] = c.nodes_a[2] = TACTA_COLLISION_NONE;
      for (int j = 0; j < 3; ++j) c.nodes_b[j] = tf[j];
      c.weights_a[0] = 1.0;
      c.weights_b[0] = 1.0 - r.u - r.v;
      c.weights_b[1] = r.u;
      c.weights_b[2] = r.v;
      c.toi = r.toi;
      finish(c, q, thickness);
    }
  }
  for (int i = 0; i < 3; ++i) {
    const uint32_t a0 = ta[i], a1 = ta[(i + 1) % 3];
    for (int j = 0; j < 3; ++j) {
      const uint32_t b0 = tb[j], b1 = tb[(j + 1) % 3];
      if (same && (a0 == b0 || a0 == b1 || a1 == b0 || a1 == b1)) continue;
      load(sa, a0, q, q + 12);
      load(sa, a1, q + 3, q + 15);
      load(sb, b0, q + 6, q + 18);
      load(sb, b1, q + 9, q + 21);
      const CcdResult r = run(false, q, method, tolerance);
      if (r.not_finite) bits |= TACTA_COLLIDE_NOT_FINITE;
      if (!r.hit) continue;
      if (count >= capacity) return bits | TACTA_COLLIDE_OVERFLOW;
      tacta_contact& c = contacts[count++];
      c = tacta_contact{};
      c.type = TACTA_CONTACT_EDGE_EDGE;
      c.index_a = a.surface;
      c.index_b = b.surface;
      c.body_a = sa.body_id;
      c.body_b = sb.body_id;
      c.feature_a = 3 * a.triangle + static_cast<uint32_t>(i);
      c.feature_b = 3 * b.triangle + static_cast<uint32_t>(j);
      c.nodes_a[0] = a0;
      c.nodes_a[1] = a1;
      c.nodes_b[0] = b0;
      c.nodes_b[1] = b1;
      c.nodes_a[2] = c.nodes_b[2] = TACTA_COLLISION_NONE;
      c.weights_a[0] = 1.0 - r.u;
      c.weights_a[1] = r.u;
      c.weights_b[0] = 1.0 - r.v;
      c.weights_b[1] = r.v;
      c.toi = r.toi;
      // finish() reads a's nodes as q points 0,1 and b's as 1..3 for vertex-face; for edges the
      // layout is a0 a1 b0 b1, so shift b's weights onto points 2 and 3.
      double qe[24];
      for (int k = 0; k < 24; ++k) qe[k] = q[k];
      tacta_contact shifted = c;
      shifted.weights_b[0] = 0.0;
      shifted.weights_b[1] = c.weights_b[0];
      shifted.weights_b[2] = c.weights_b[1];
      finish(shifted, qe, thickness);
      for (int k = 0; k < 3; ++k) {
        c.point[k] = shifted.point[k];
        c.normal[k] = shifted.normal[k];
      }
      c.depth = shifted.depth;
    }
  }
  return bits;
}

}  // namespace tacta::collision
