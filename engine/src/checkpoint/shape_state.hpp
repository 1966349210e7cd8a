// A body's shape in a checkpoint: its cut totals and what its recordings follow, and, once a cut
// changed its mesh, the whole cut topology (rest mesh, held nodes, cut tags, crack, embedded
// surface). An uncut body's mesh is the scene's, which the fingerprint covers.
#pragma once

#include <cstddef>

#include "checkpoint/checkpoint_format.hpp"
#include "world/world.hpp"

namespace tacta {

void save_shape(CheckpointWriter& out, const SoftBody& b);

// Reads the shape `save_shape` wrote for body `slot` and gives the body that shape when it
// differs from the one it has: the saved cut topology, or the scene's when the checkpoint's body
// was uncut and this one was cut since. Everything read is checked before anything changes
// (topology_problems, the surface's binding to its tets, every index against its array); the
// models are rebuilt on the new mesh and not begun (their saved state comes next). Returns
// whether the body was reshaped (its collision surface, proxies and render description must
// follow).
bool load_shape(CheckpointReader& in, World& world, size_t slot);

// After the body's node positions were read: its embedded surface made current from them.
void shape_positions_loaded(const SoftBody& b);

}  // namespace tacta
