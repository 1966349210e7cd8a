// Surface vertices against rigid shapes: the moving tools (world.shapes) and the static
// obstacles (world.obstacles). The `detect` entry of plugin "convex" with pairs == NULL.
//
// A vertex is in contact with a shape when its signed distance to the shape at the end of the
// tick is below the surface's thickness h. The relative motion of the vertex in the shape's
// frame (start pose to end pose) is also swept, by conservative advancement on the exact
// signed distance (1-Lipschitz, so no step jumps over the shape), so that a vertex that passed
// through a thin tool or obstacle during the tick is caught at its entry point; its contact
// then carries the normal and point of the entry side (the side it came from).
// Sphere, capsule, box and plane use exact analytic distances; a hull (points only, possibly
// rounded) goes through the caller's callback (libccd), at the end of the tick only.
// Contact: type SHAPE_VERTEX (index_b into shapes) or OBSTACLE_VERTEX (into obstacles),
// nodes_a = {vertex}, point on the shape at the end of the tick, normal from the shape towards
// the vertex, depth = h - signed distance along the normal (> 0 when inside the layer).
// Fixed vertices (inverse mass 0) are skipped: neither side can move.
#pragma once

#include <cstdint>

#include "tacta/collision_api.h"

namespace tacta::collision {

// Hull query: signed distance d (m) of world point x to the hull at its end pose when it is
// below `reach` (m), with the unit outward normal and the closest surface point. Returns false
// when farther than reach (or on failure).
using HullDistance = bool (*)(void* context, const tacta_collision_shape& hull, const double* x,
                              double reach, double& distance, double* normal, double* point);

// Appends contacts to contacts[count..capacity); returns TACTA_COLLIDE_* bits.
uint32_t vertex_shape_contacts(const tacta_collision_world& world, HullDistance hull_distance,
                               void* hull_context, tacta_contact* contacts, uint32_t capacity,
                               uint32_t& count) noexcept;

}  // namespace tacta::collision
