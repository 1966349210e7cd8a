#include "contact_response.hpp"

#include <algorithm>
#include <cmath>

#include "tacta/sdk/pose.hpp"
#include "tacta/vec3.hpp"

namespace tacta::collision {
namespace {

// One side of a contact: up to three vertices of a surface, or a point on a rigid shape.
struct Side {
  tacta_collision_surface* surface = nullptr;  // null: rigid (tool or obstacle)
  const tacta_collision_shape* shape = nullptr;
  uint32_t nodes[3] = {0, 0, 0};
  double weights[3] = {0, 0, 0};
  int count = 0;
};

// A contact bound to the world: both sides, the unit normal and the thickness.
struct Constraint {
  Side a, b;
  double normal[3] = {0, 0, 0};
  double thickness = 0;           // m
  const double* point = nullptr;  // m, rigid side's contact point at the end of the tick
};

double inverse_mass(const tacta_collision_surface& s, uint32_t v) {
  return s.inverse_masses != nullptr ? s.inverse_masses[v] : 1.0;
}

uint32_t bind_side(tacta_collision_world& world, uint32_t surface, const uint32_t* nodes,
                   const double* weights, Side& side) {
  if (surface >= world.surface_count || world.surfaces == nullptr) return TACTA_COLLIDE_DEGENERATE;
  side.surface = &world.surfaces[surface];
  side.count = 0;
  for (int k = 0; k < 3; ++k) {
    if (nodes[k] == TACTA_COLLISION_NONE) continue;
    if (nodes[k] >= side.surface->vertex_count) return TACTA_COLLIDE_DEGENERATE;
    if (!std::isfinite(weights[k])) return TACTA_COLLIDE_NOT_FINITE;
    const double* x = side.surface->positions_end + 3 * nodes[k];
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      return TACTA_COLLIDE_NOT_FINITE;
    if (!std::isfinite(inverse_mass(*side.surface, nodes[k]))) return TACTA_COLLIDE_NOT_FINITE;
    side.nodes[side.count] = nodes[k];
    side.weights[side.count] = weights[k];
    ++side.count;
  }
  return side.count > 0 ? 0u : TACTA_COLLIDE_DEGENERATE;
}

// Fills k from contact c; returns nonzero bits when the contact must be skipped.
uint32_t bind(tacta_collision_world& world, const tacta_contact& c, Constraint& k) {
  k = Constraint{};
  if (c.type != TACTA_CONTACT_VERTEX_FACE && c.type != TACTA_CONTACT_EDGE_EDGE &&
      c.type != TACTA_CONTACT_SHAPE_VERTEX && c.type != TACTA_CONTACT_OBSTACLE_VERTEX)
    return TACTA_COLLIDE_DEGENERATE;
  if (const uint32_t bits = bind_side(world, c.index_a, c.nodes_a, c.weights_a, k.a)) return bits;
  k.thickness = k.a.surface->thickness;
  if (c.type == TACTA_CONTACT_SHAPE_VERTEX || c.type == TACTA_CONTACT_OBSTACLE_VERTEX) {
    const bool tool = c.type == TACTA_CONTACT_SHAPE_VERTEX;
    const uint32_t available = tool ? world.shape_count : world.obstacle_count;
    const tacta_collision_shape* shapes = tool ? world.shapes : world.obstacles;
    if (c.index_b >= available || shapes == nullptr) return TACTA_COLLIDE_DEGENERATE;
    k.b.shape = &shapes[c.index_b];
    k.point = c.point;
    if (!std::isfinite(c.point[0]) || !std::isfinite(c.point[1]) || !std::isfinite(c.point[2]))
      return TACTA_COLLIDE_NOT_FINITE;
  } else {
    if (const uint32_t bits = bind_side(world, c.index_b, c.nodes_b, c.weights_b, k.b)) return bits;
    k.thickness = std::max(k.thickness, k.b.surface->thickness);
  }
  if (!std::isfinite(k.thickness) || k.thickness < 0) return TACTA_COLLIDE_DEGENERATE;
  const double length = std::sqrt(dot(c.normal, c.normal));
  if (!std::isfinite(length)) return TACTA_COLLIDE_NOT_FINITE;
  if (length < 0.5) return TACTA_COLLIDE_DEGENERATE;  // no usable direction (parallel edges)
  for (int i = 0; i < 3; ++i) k.normal[i] = c.normal[i] / length;
  return 0;
}

// The contact point of a side at the end of the tick (m).
void side_point(const Side& s, const double* rigid_point, double* out) {
  if (s.surface == nullptr) {
    for (int i = 0; i < 3; ++i) out[i] = rigid_point[i];
    return;
  }
  out[0] = out[1] = out[2] = 0;
  for (int j = 0; j < s.count; ++j)
    for (int i = 0; i < 3; ++i)
      out[i] += s.weights[j] * s.surface->positions_end[3 * s.nodes[j] + i];
}

double weighted_inverse_mass(const Side& s) {
  double w = 0;
  if (s.surface != nullptr)
    for (int j = 0; j < s.count; ++j)
      w += s.weights[j] * s.weights[j] * inverse_mass(*s.surface, s.nodes[j]);
  return w;
}

double violation(const Constraint& k) {
  double xa[3], xb[3];
  side_point(k.a, nullptr, xa);
  side_point(k.b, k.point, xb);
  const double gap[3] = {xa[0] - xb[0], xa[1] - xb[1], xa[2] - xb[2]};
  return dot(gap, k.normal) - k.thickness;
}

// Moves side s by sign * w_j / m_j * delta (m) on every vertex: positions (or velocities).
void move_side(const Side& s, double* field, double sign, const double* delta) {
  if (s.surface == nullptr || field == nullptr) return;
  for (int j = 0; j < s.count; ++j) {
    const double scale = sign * s.weights[j] * inverse_mass(*s.surface, s.nodes[j]);
    for (int i = 0; i < 3; ++i) field[3 * s.nodes[j] + i] += scale * delta[i];
  }
}

using sdk::rotate;

// Velocity of a side's contact point (m/s); a rigid side moves its material point from the
// start pose to the end pose over the tick.
bool side_velocity(const Side& s, const double* rigid_point, double dt, double* out) {
  out[0] = out[1] = out[2] = 0;
  if (s.surface != nullptr) {
    if (s.surface->velocities == nullptr) return false;
    for (int j = 0; j < s.count; ++j)
      for (int i = 0; i < 3; ++i)
        out[i] += s.weights[j] * s.surface->velocities[3 * s.nodes[j] + i];
    return true;
  }
  if (s.shape->type == TACTA_SHAPE_PLANE || !(dt > 0)) return true;  // static
  const tacta_pose& p0 = s.shape->pose_start;
  const tacta_pose& p1 = s.shape->pose_end;
  const double offset[3] = {rigid_point[0] - p1.position[0], rigid_point[1] - p1.position[1],
                            rigid_point[2] - p1.position[2]};
  double local[3], start[3];
  rotate(p1.rotation, offset, true, local);
  rotate(p0.rotation, local, false, start);
  for (int i = 0; i < 3; ++i) {
    out[i] = (rigid_point[i] - (p0.position[i] + start[i])) / dt;
    if (!std::isfinite(out[i])) out[i] = 0;
  }
  return true;
}

// One sequential-impulse update of contact c (accumulated impulse on a stored in c.force).
void apply_impulses(Constraint& k, tacta_contact& c, double friction, double dt) {
  const double w = weighted_inverse_mass(k.a) + weighted_inverse_mass(k.b);
  double va[3], vb[3];
  if (!(w > 0) || !side_velocity(k.a, nullptr, dt, va) || !side_velocity(k.b, k.point, dt, vb))
    return;
  const double* n = k.normal;
  double* accumulated = c.force;
  double rel[3] = {va[0] - vb[0], va[1] - vb[1], va[2] - vb[2]};
  // Normal: remove the approaching component, never pull.
  const double normal_old = dot(accumulated, n);
  const double normal_new = std::max(normal_old - dot(rel, n) / w, 0.0);
  double impulse[3];
  for (int i = 0; i < 3; ++i) impulse[i] = (normal_new - normal_old) * n[i];
  // Tangential: aim at zero sliding, within the Coulomb cone of the normal impulse.
  const double rel_n = dot(rel, n) + (normal_new - normal_old) * w;
  double tangent_old[3], tangent_new[3];
  for (int i = 0; i < 3; ++i) {
    tangent_old[i] = accumulated[i] - normal_old * n[i];
    const double slide = rel[i] + impulse[i] * w - rel_n * n[i];
    tangent_new[i] = tangent_old[i] - slide / w;
  }
  const double limit = friction * normal_new;
  const double magnitude = std::sqrt(dot(tangent_new, tangent_new));
  if (magnitude > limit)
    for (double& t : tangent_new) t *= magnitude > 0 ? limit / magnitude : 0.0;
  double friction_change[3];
  for (int i = 0; i < 3; ++i) {
    friction_change[i] = tangent_new[i] - tangent_old[i];
    impulse[i] += friction_change[i];
    accumulated[i] = normal_new * n[i] + tangent_new[i];
  }
  move_side(k.a, k.a.surface->velocities, 1.0, impulse);
  if (k.b.surface != nullptr) move_side(k.b, k.b.surface->velocities, -1.0, impulse);
  // Friction also displaces the end positions, as the corrected velocity would have.
  double displacement[3];
  for (int i = 0; i < 3; ++i) displacement[i] = friction_change[i] * dt;
  move_side(k.a, k.a.surface->positions_end, 1.0, displacement);
  if (k.b.surface != nullptr) move_side(k.b, k.b.surface->positions_end, -1.0, displacement);
}

void project(const Constraint& k) {
  const double c = violation(k);
  if (!(c < 0)) return;
  const double w = weighted_inverse_mass(k.a) + weighted_inverse_mass(k.b);
  if (!(w > 0)) return;
  const double lambda = -c / w;
  const double delta[3] = {lambda * k.normal[0], lambda * k.normal[1], lambda * k.normal[2]};
  move_side(k.a, k.a.surface->positions_end, 1.0, delta);
  if (k.b.surface != nullptr) move_side(k.b, k.b.surface->positions_end, -1.0, delta);
}

// CCD-limited motion with time of impact 0: free vertices back to their start positions.
void restart_side(const Side& s) {
  if (s.surface == nullptr) return;
  for (int j = 0; j < s.count; ++j) {
    if (inverse_mass(*s.surface, s.nodes[j]) <= 0) continue;
    for (int i = 0; i < 3; ++i)
      s.surface->positions_end[3 * s.nodes[j] + i] = s.surface->positions_start[3 * s.nodes[j] + i];
  }
}

}  // namespace

uint32_t respond_to_contacts(tacta_collision_world& world, tacta_contact* contacts,
                             uint32_t contact_count, const ResponseSettings& settings) noexcept {
  if (contacts == nullptr || contact_count == 0) return TACTA_COLLIDE_OK;
  uint32_t bits = 0;
  Constraint k;
  for (uint32_t i = 0; i < contact_count; ++i)
    for (double& f : contacts[i].force) f = 0;
  for (uint32_t pass = 0; pass < settings.iterations; ++pass)
    for (uint32_t i = 0; i < contact_count; ++i) {
      const uint32_t skipped = bind(world, contacts[i], k);
      if (pass == 0) bits |= skipped;
      if (skipped == 0) project(k);
    }
  for (uint32_t pass = 0; pass < settings.iterations; ++pass)
    for (uint32_t i = 0; i < contact_count; ++i)
      if (bind(world, contacts[i], k) == 0)
        apply_impulses(k, contacts[i], settings.friction, world.dt);
  // Friction displaced positions tangentially to its own contact, which can tilt into a
  // neighbour's normal: project again.
  for (uint32_t pass = 0; pass < settings.iterations; ++pass)
    for (uint32_t i = 0; i < contact_count; ++i)
      if (bind(world, contacts[i], k) == 0) project(k);
  const double dt = world.dt > 0 ? world.dt : 1.0;
  for (uint32_t i = 0; i < contact_count; ++i) {
    tacta_contact& c = contacts[i];
    for (double& f : c.force) f /= dt;
    if (bind(world, c, k) != 0) continue;
    // Nothing movable (fixed vertices against a rigid side or each other): not ours to resolve.
    if (!(weighted_inverse_mass(k.a) + weighted_inverse_mass(k.b) > 0)) continue;
    if (k.b.surface == nullptr) {  // rigid side: kept at the thickness
      if (violation(k) < -settings.tolerance) bits |= TACTA_COLLIDE_UNRESOLVED;
      continue;
    }
    // Surface-surface: inside the layer is allowed (CCD sees crossings, not proximity); a point
    // past the other side falls back to the contact-free start.
    if (violation(k) + k.thickness >= -settings.tolerance) continue;
    restart_side(k.a);
    restart_side(k.b);
    if (violation(k) + k.thickness < -settings.tolerance) bits |= TACTA_COLLIDE_UNRESOLVED;
  }
  return bits;
}

}  // namespace tacta::collision
