// A cut applied to one body of the world: the topology edit (topology/cut_mesh.hpp) computed against
// the body's current shape, and everything derived from its mesh made again from the edit, on the
// thread that runs the ticks, between two ticks. What lies outside the world (the collision
// surface, the haptic proxies, the render description) is brought up to date by the caller
// (Simulation::cut).
#pragma once

#include <cstddef>
#include <span>

#include "tacta/sim/cut.hpp"
#include "world/world.hpp"

namespace tacta {

// Cuts body `slot` along `triangles` (9 doubles each, m, world frame) at simulated `time` (s):
// a new rest mesh, lumped masses, fixed nodes, model instance (rebuilt on the new mesh from the
// parameters of the one in use, then begun from the carried-over state), node state and loads,
// recorded nodes, probes and embedded surface. Allocates. Throws InputError (nothing changed)
// when the body cannot be cut: a model without TACTA_MODEL_CLAIM_TOPOLOGY_EDITS, a body on its
// own thread or with prescribed motion or plates, a model swap waiting, a planar mesh, or a
// removal that would take every tet.
CutSummary cut_body(World& world, size_t slot, std::span<const double> triangles, CutMode mode,
                    double time);

}  // namespace tacta
