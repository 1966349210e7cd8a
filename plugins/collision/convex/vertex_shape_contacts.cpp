#include "vertex_shape_contacts.hpp"

#include <algorithm>
#include <cmath>

#include "tacta/sdk/pose.hpp"
#include "tacta/vec3.hpp"

namespace tacta::collision {
namespace {

constexpr int kAdvanceSteps = 64;  // conservative advancement: grazing paths stop here (no hit)

bool finite3(const double* a) {
  return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}

using sdk::rotate;

void to_local(const tacta_pose& pose, const double* x, double* local) {
  const double offset[3] = {x[0] - pose.position[0], x[1] - pose.position[1],
                            x[2] - pose.position[2]};
  rotate(pose.rotation, offset, true, local);
}

void to_world(const tacta_pose& pose, const double* local, bool is_point, double* x) {
  rotate(pose.rotation, local, false, x);
  if (is_point)
    for (int i = 0; i < 3; ++i) x[i] += pose.position[i];
}

// Exact signed distance (m) of a local point to an analytic shape, with the outward normal.
double signed_distance(const tacta_collision_shape& s, const double* p, double* n) {
  double q[3] = {0, 0, 0};  // closest point of the core (sphere centre, capsule segment)
  if (s.type == TACTA_SHAPE_BOX) {
    double outside[3], inner = -1e300;
    int axis = 0;
    for (int i = 0; i < 3; ++i) {
      const double d = std::fabs(p[i]) - s.half_extents[i];
      outside[i] = std::max(d, 0.0);
      if (d > inner) inner = d, axis = i;
    }
    const double out = norm(outside);
    if (out > 0) {
      for (int i = 0; i < 3; ++i) n[i] = (p[i] < 0 ? -outside[i] : outside[i]) / out;
      return out;
    }
    n[0] = n[1] = n[2] = 0;
    n[axis] = p[axis] < 0 ? -1.0 : 1.0;
    return inner;
  }
  if (s.type == TACTA_SHAPE_CAPSULE) q[2] = std::clamp(p[2], -s.half_length, s.half_length);
  const double d[3] = {p[0] - q[0], p[1] - q[1], p[2] - q[2]};
  const double length = norm(d);
  if (length > 0) {
    for (int i = 0; i < 3; ++i) n[i] = d[i] / length;
  } else {  // on the core: any direction is the deepest; take one across a capsule's axis
    n[0] = s.type == TACTA_SHAPE_CAPSULE ? 1.0 : 0.0;
    n[1] = 0;
    n[2] = s.type == TACTA_SHAPE_CAPSULE ? 0.0 : 1.0;
  }
  return length - s.radius;
}

// Radius (m) of a sphere about the pose origin that holds the shape.
double bounding_radius(const tacta_collision_shape& s) {
  switch (s.type) {
    case TACTA_SHAPE_SPHERE: return s.radius;
    case TACTA_SHAPE_CAPSULE: return s.half_length + s.radius;
    case TACTA_SHAPE_BOX: return norm(s.half_extents);
    case TACTA_SHAPE_HULL: {
      double r = 0;
      for (uint32_t i = 0; s.points != nullptr && i < s.point_count; ++i)
        r = std::max(r, norm(s.points + 3 * i));
      return r + s.radius;
    }
    default: return 0;
  }
}

// Distance (m) from the origin to the segment a-b.
double segment_origin_distance(const double* a, const double* b) {
  const double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double dd = dot(d, d);
  const double t = dd > 0 ? std::clamp(-dot(a, d) / dd, 0.0, 1.0) : 0.0;
  const double c[3] = {a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]};
  return norm(c);
}

struct Found {
  double toi = 1.0;
  double distance = 0;  // m, signed, at the contact position
  double normal[3] = {0, 0, 1};
  double point[3] = {0, 0, 0};  // world, on the shape at the end of the tick
};

// Vertex moving start -> end (world) against one analytic or hull shape; true on contact.
bool vertex_against(const tacta_collision_shape& s, double reach_radius, const double* start,
                    const double* end, double h, HullDistance hull, void* hull_context, Found& f) {
  if (s.type == TACTA_SHAPE_PLANE) {
    const double d = dot(s.plane_normal, end) - s.plane_offset;
    if (!(d < h)) return false;
    for (int i = 0; i < 3; ++i) {
      f.normal[i] = s.plane_normal[i];
      f.point[i] = end[i] - d * s.plane_normal[i];
    }
    f.distance = d;
    f.toi = 1.0;
    return true;
  }
  if (s.type == TACTA_SHAPE_HULL) {
    if (hull == nullptr || s.points == nullptr || s.point_count == 0) return false;
    double local[3];
    to_local(s.pose_end, end, local);
    if (norm(local) > reach_radius + h) return false;
    if (!hull(hull_context, s, end, h, f.distance, f.normal, f.point)) return false;
    f.toi = 1.0;
    return f.distance < h;
  }
  double p0[3], p1[3], n[3];
  to_local(s.pose_start, start, p0);
  to_local(s.pose_end, end, p1);
  if (segment_origin_distance(p0, p1) > reach_radius + h) return false;
  double at[3] = {p1[0], p1[1], p1[2]};
  double d = signed_distance(s, p1, n);
  const bool end_inside = d < h;
  f.toi = 1.0;
  const double length =
      std::sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) + (p1[1] - p0[1]) * (p1[1] - p0[1]) +
                (p1[2] - p0[2]) * (p1[2] - p0[2]));
  double n0[3];
  if (length > 0 && !(signed_distance(s, p0, n0) < h)) {
    // The vertex started clear: find where its relative motion first enters the layer, so that
    // a vertex that went in (or through) is sent back to the side it came from.
    double t = 0, dt_entry = 0, n_entry[3] = {0, 0, 1}, entry[3] = {p0[0], p0[1], p0[2]};
    bool hit = false;
    for (int step = 0; step < kAdvanceSteps && t <= 1.0; ++step) {
      for (int i = 0; i < 3; ++i) entry[i] = p0[i] + t * (p1[i] - p0[i]);
      dt_entry = signed_distance(s, entry, n_entry);
      if (dt_entry - h <= 1e-3 * h + 1e-12) {
        hit = true;
        break;
      }
      t += (dt_entry - h) / length;
    }
    if (hit) {
      f.toi = std::clamp(t, 0.0, 1.0);
      d = dt_entry;
      for (int i = 0; i < 3; ++i) at[i] = entry[i], n[i] = n_entry[i];
    } else if (!end_inside) {
      return false;
    }
  } else if (!end_inside) {
    return false;
  }
  double surface_local[3];
  for (int i = 0; i < 3; ++i) surface_local[i] = at[i] - d * n[i];
  to_world(s.pose_end, surface_local, true, f.point);
  to_world(s.pose_end, n, false, f.normal);
  f.distance = dot(f.normal, end) - dot(f.normal, f.point);
  return true;
}

}  // namespace

uint32_t vertex_shape_contacts(const tacta_collision_world& world, HullDistance hull_distance,
                               void* hull_context, tacta_contact* contacts, uint32_t capacity,
                               uint32_t& count) noexcept {
  uint32_t bits = 0;
  for (int group = 0; group < 2; ++group) {
    const bool tools = group == 0;
    const tacta_collision_shape* shapes = tools ? world.shapes : world.obstacles;
    const uint32_t shape_count = tools ? world.shape_count : world.obstacle_count;
    if (shapes == nullptr) continue;
    for (uint32_t b = 0; b < shape_count; ++b) {
      const tacta_collision_shape& s = shapes[b];
      if (!finite3(s.pose_start.position) || !finite3(s.pose_end.position) ||
          !finite3(s.plane_normal)) {
        bits |= TACTA_COLLIDE_NOT_FINITE;
        continue;
      }
      if (s.type < TACTA_SHAPE_SPHERE || s.type > TACTA_SHAPE_PLANE) {
        bits |= TACTA_COLLIDE_DEGENERATE;
        continue;
      }
      const double reach = bounding_radius(s);
      for (uint32_t a = 0; a < world.surface_count && world.surfaces != nullptr; ++a) {
        const tacta_collision_surface& surface = world.surfaces[a];
        const double h = surface.thickness;
        for (uint32_t v = 0; v < surface.vertex_count; ++v) {
          // A fixed vertex against a rigid shape: nothing can move, no contact to resolve.
          if (surface.inverse_masses != nullptr && surface.inverse_masses[v] == 0.0) continue;
          const double* start = surface.positions_start + 3 * v;
          const double* end = surface.positions_end + 3 * v;
          if (!finite3(start) || !finite3(end)) {
            bits |= TACTA_COLLIDE_NOT_FINITE;
            continue;
          }
          Found f;
          if (!vertex_against(s, reach, start, end, h, hull_distance, hull_context, f)) continue;
          if (!finite3(f.normal) || !finite3(f.point)) {
            bits |= TACTA_COLLIDE_NOT_FINITE;
            continue;
          }
          if (count >= capacity) return bits | TACTA_COLLIDE_OVERFLOW;
          tacta_contact& c = contacts[count++];
          c = tacta_contact{};
          c.type = tools ? TACTA_CONTACT_SHAPE_VERTEX : TACTA_CONTACT_OBSTACLE_VERTEX;
          c.index_a = a;
          c.index_b = b;
          c.body_a = surface.body_id;
          c.body_b = s.body_id;
          c.feature_a = v;
          c.feature_b = TACTA_COLLISION_NONE;
          c.nodes_a[0] = v;
          c.nodes_a[1] = c.nodes_a[2] = c.nodes_b[0] = c.nodes_b[1] = c.nodes_b[2] =
              TACTA_COLLISION_NONE;
          c.weights_a[0] = 1.0;
          c.toi = f.toi;
          for (int i = 0; i < 3; ++i) {
            c.point[i] = f.point[i];
            c.normal[i] = f.normal[i];
          }
          c.depth = h - f.distance;
        }
      }
    }
  }
  return bits;
}

}  // namespace tacta::collision
