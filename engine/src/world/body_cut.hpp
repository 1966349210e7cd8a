// A cut applied to one body of the world: the topology edit (topology/cut_mesh.hpp) computed against
// the body's current shape, and everything derived from its mesh made again from the edit, on the
// thread that runs the ticks, between two ticks. What lies outside the world (the collision
// surface, the haptic proxies, the render description) is brought up to date by the caller
// (Simulation::cut).
#pragma once

#include <cstddef>
#include <span>
#include <string>

#include "tacta/sim/cut.hpp"
#include "world/world.hpp"

namespace tacta {

// Cuts body `slot` along `triangles` (9 doubles each, m, world frame) at simulated `time` (s):
// a new rest mesh, lumped masses, fixed nodes, model instance (rebuilt on the new mesh from the
// parameters of the one in use, then begun from the carried-over state), node state and loads,
// recorded nodes, probes and embedded surface. Allocates. Throws InputError (nothing changed)
// when the body cannot be cut: a model without TACTA_MODEL_CLAIM_TOPOLOGY_EDITS, a body on its
// own thread or with prescribed motion or plates, a model swap waiting, and what cut_mesh refuses
// (a planar mesh, blade numbers not 9 a triangle, a removal that would take every tet).
// Why body `b` can never be cut as the scene set it up (its own thread, prescribed motion or
// plates, a model without TACTA_MODEL_CLAIM_TOPOLOGY_EDITS); empty when it can. A scene's cut
// events are checked by it at load, every cut again when it comes.
std::string cut_unsupported(const SoftBody& b);

CutSummary cut_body(World& world, size_t slot, std::span<const double> triangles, CutMode mode,
                    double time);

}  // namespace tacta
