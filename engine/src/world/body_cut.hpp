// A cut applied to one body of the world: the topology edit (topology/cut_mesh.hpp) computed against
// the body's current shape, and everything derived from its mesh made again from the edit, on the
// thread that runs the ticks, between two ticks. What lies outside the world (the collision
// surface, the haptic proxies, the render description) is brought up to date by the caller
// (Simulation::cut).
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "tacta/sim/cut.hpp"
#include "world/world.hpp"

namespace tacta {

// Why body `b` can never be cut as the scene set it up (its own thread, a model without
// TACTA_MODEL_CLAIM_TOPOLOGY_EDITS); empty when it can. A scene's cut events are checked by it at
// load, every cut again when it comes.
std::string cut_unsupported(const SoftBody& b);

// Cuts body `slot` along `triangles` (9 doubles each, m, world frame) at simulated `time` (s):
// a new rest mesh, lumped masses, fixed nodes, model instance (rebuilt on the new mesh from the
// parameters of the one in use, then begun from the carried-over state), node state and loads,
// boundary motion, recorded nodes, probes and embedded surface. Allocates. Throws InputError
// (nothing changed) when the body cannot be cut: cut_unsupported, a model swap waiting, and what
// cut_mesh refuses (a planar mesh, blade numbers not 9 a triangle, a removal that would take
// every tet).
CutSummary cut_body(World& world, size_t slot, std::span<const double> triangles, CutMode mode,
                    double time);

// What a body's shape becomes (from a cut or a checkpoint): the rest mesh with its masses and
// held nodes, the boundary triangles cuts made (1 each; empty: none), the crack, per node the
// loaded mesh's node it copies, the embedded surface and the boundary motion on the new mesh
// (null: the body has none).
struct NewShape {
  std::unique_ptr<BodyTopology> topology;
  std::unique_ptr<EmbeddedSurface> surface;
  std::vector<uint8_t> cut_triangles;
  std::vector<std::array<uint32_t, 3>> crack;
  std::vector<uint32_t> loaded_node;
  std::unique_ptr<BoundaryMotion> boundary;
};

// Body `b`'s models made on `topology` with the parameters of the ones it has: the instance in
// use and the scheduled swaps still to come. Throws InputError at `where` (nothing changed).
struct ShapeModels {
  std::unique_ptr<ModelInstance> instance;
  std::vector<std::unique_ptr<ModelInstance>> future_swaps;
};
ShapeModels make_shape_models(World& world, const SoftBody& b, const BodyTopology& topology,
                              const SourceLocation& where);

// Gives body `b` the new shape, its models (not begun) and node arrays (3 per node of the new
// mesh; the loads become zero, the applied forces are the caller's); the old topology, arrays,
// surface and boundary motion are kept as RetiredArrays. The embedded surface is made current
// from `positions`.
// Allocates; throws nothing.
void install_shape(const SoftBody& b, NewShape shape, ShapeModels models,
                   std::vector<double> positions, std::vector<double> velocities,
                   std::vector<double> step_start);

}  // namespace tacta
