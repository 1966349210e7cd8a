// Contact response for the contacts of one tick (the `respond` entry of plugin "ccd").
//
// Method: CCD-limited motion plus position projection, then velocity impulses with friction.
//
// Every contact is read as a one-sided constraint on the end-of-tick positions
//     C = (x_a - x_b) . n - h >= 0
// x_a, x_b: the contact points as barycentric combinations (weights_a, weights_b) of the
// vertices' end positions; for a rigid side (tool, obstacle) x_b is the stored contact point on
// the shape at the end of the tick. n: the contact normal from b towards a, which the narrow
// phases orient by the side a was on at the start of the tick, so a vertex that crossed a face
// during the tick is brought back to its own side. h: the thickness (m) of the surfaces.
//
//  1. Positions, `iterations` Gauss-Seidel passes: a violated constraint is projected out along
//     n with lambda = -C / W, W = sum over both sides of w_i^2 / m_i; vertex i moves by
//     w_i lambda n / m_i (b's vertices by the opposite). Each side's weights sum to 1, so
//     sum_i m_i dx_i = 0: deformable-deformable projection keeps momentum and centre of mass.
//     Fixed vertices (1/m = 0) never move; a rigid side has 1/m = 0 (the host moves tools).
//  2. Velocities, `iterations` passes of sequential impulses on the same constraints: the
//     approaching normal relative velocity is removed (inelastic; the accumulated normal impulse
//     is clamped >= 0), then the tangential relative velocity is reduced by Coulomb friction
//     (accumulated tangential impulse clamped to mu times the normal one). The friction's
//     velocity change also moves the end positions (dx = dv dt), so static friction holds.
//  3. Positions again, `iterations` passes: friction moved vertices tangentially to their own
//     contact, which may tilt into a neighbouring contact's normal.
//  4. CCD-limited motion, the fallback: a surface-surface contact whose point is still past the
//     other side (C < -h - tolerance) after the passes (conflicting constraints) puts the free
//     vertices of both sides back at their start-of-tick positions (time of impact 0: the start
//     of the tick was contact-free, the previous tick ended so and CCD checked the motion
//     since). A contact still violated then, or a rigid-side contact with C < -tolerance,
//     sets TACTA_COLLIDE_UNRESOLVED (not when all its vertices are fixed: nothing can move).
//     Surface-surface contacts may end inside the thickness layer (0 < gap < h): CCD reports
//     crossings, not proximity, so nothing pushes them out there.
//  The positions changed here are checked again by the caller's next detection round (the
//  engine runs detect + respond again while surface-surface contacts appear, see
//  collision_context.cpp), which catches crossings the corrections themselves create.
//
// contact.force: the accumulated velocity impulse on a divided by dt (N); b receives the
// opposite. The position projection is a geometric correction and does not count as force.
// No allocation, no exception; O(iterations x contacts).
#pragma once

#include <cstdint>

#include "tacta/collision_api.h"

namespace tacta::collision {

struct ResponseSettings {
  double friction = 0.3;    // Coulomb coefficient (dimensionless)
  uint32_t iterations = 8;  // Gauss-Seidel passes, positions then velocities
  double tolerance = 1e-7;  // m: residual violation accepted after the passes
};

// Corrects positions_end and velocities of world's surfaces; writes contacts[i].force.
// Returns TACTA_COLLIDE_* bits (DEGENERATE / NOT_FINITE contacts are skipped).
uint32_t respond_to_contacts(tacta_collision_world& world, tacta_contact* contacts,
                             uint32_t contact_count, const ResponseSettings& settings) noexcept;

}  // namespace tacta::collision
