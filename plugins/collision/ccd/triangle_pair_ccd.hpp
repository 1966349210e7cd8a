// Exact CCD between two moving triangles of the world: the 6 vertex-face and 9 edge-edge
// primitive tests, each turned into a tacta_contact.
#pragma once

#include "inclusion_ccd.hpp"
#include "tacta/collision_api.h"

namespace tacta::collision {

enum class CcdMethod { kInclusion, kPlain };

struct TriangleRef {
  uint32_t surface;
  uint32_t triangle;
};

// Appends contacts of triangle a against triangle b to contacts[count..capacity); returns
// TACTA_COLLIDE_* bits (OVERFLOW when full, NOT_FINITE / DEGENERATE when skipped).
uint32_t triangle_pair_contacts(const tacta_collision_world& world, TriangleRef a, TriangleRef b,
                                CcdMethod method, const CcdTolerance& tolerance,
                                tacta_contact* contacts, uint32_t capacity,
                                uint32_t& count) noexcept;

}  // namespace tacta::collision
