// A cut applied to one body of the world: the topology edit (topology/cut_mesh.hpp) computed against
// the body's current shape, and everything derived from its mesh made again from the edit. It comes
// in two halves so that what allocates need not run on the thread that ticks: prepare_cut builds
// the new shape from what no tick changes (the rest mesh, the crack, the models' parameters) and a
// copy of the positions; apply_cut installs it at a tick boundary from the body's state then,
// allocating nothing; retire_cut keeps what it replaced. cut_body does all three between two
// ticks. What lies outside the world (the collision surface, the haptic proxies, the render
// description) is brought up to date by the caller (Simulation::cut).
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "boundary/probes.hpp"
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
// use and the scheduled swaps still to come (future_swaps: one per scheduled swap, null for those
// already made). Throws InputError at `where` (nothing changed).
struct ShapeModels {
  std::unique_ptr<ModelInstance> instance;
  std::vector<std::unique_ptr<ModelInstance>> future_swaps;
};
ShapeModels make_shape_models(World& world, const SoftBody& b, const BodyTopology& topology,
                              const SourceLocation& where);

// A body's node arrays for a new shape, 3 per node: state and loads.
struct ShapeArrays {
  std::vector<double> positions, velocities, step_start;
  std::vector<double> external_forces, contact_forces, applied_forces;  // applied: empty or 3/node
};

// Gives body `b` the new shape, its models (not begun) and node arrays by exchange: afterwards
// `shape`, `models` and `arrays` hold what the body had (the old instance, its scheduled swaps and
// those already made). The embedded surface is made current from the new positions. Allocates
// nothing, throws nothing.
void exchange_shape(const SoftBody& b, NewShape& shape, ShapeModels& models,
                    ShapeArrays& arrays) noexcept;

// exchange_shape with the loads zero and no applied force, then the old topology, positions,
// velocities, surface and boundary motion kept as RetiredArrays (a checkpoint's restore).
// Allocates; throws nothing.
void install_shape(const SoftBody& b, NewShape shape, ShapeModels models,
                   std::vector<double> positions, std::vector<double> velocities,
                   std::vector<double> step_start);

// A cut's first half, made from body `slot`'s rest data and `positions` and `velocities` (3 per
// node: its state when the cut was asked for). Holds, once applied, what the body had.
struct PreparedCut {
  size_t slot = 0;
  CutMode mode = CutMode::kSeparate;
  bool changed = false;  // false: the blade missed (only the crack and cuts_missed change)
  std::vector<std::array<uint32_t, 3>> crack;  // unchanged cut: the crack it leaves
  size_t tets_removed = 0, nodes_removed = 0, nodes_added = 0, faces_separated = 0;
  double removed_mass_kg = 0;         // the rest masses the edit took away (removal)
  std::vector<uint32_t> node_source;  // per new node: the old node it continues
  std::vector<int64_t> first_copy;    // per old node: its first copy, -1 when it went
  // The body's recordings carried to the new mesh.
  std::vector<uint32_t> recorded_nodes;
  std::optional<uint32_t> probe_node;
  std::vector<Probe> probes;
  NewShape shape;
  ShapeArrays arrays;  // sized for the new mesh; apply_cut fills them
  // The state the cut was asked at, and the energy (J, kinetic + elastic) the new shape holds
  // there: retire_cut books what the cut took (the old model's energy there, less this one).
  std::vector<double> positions_then, velocities_then;
  double energy_after_J = 0;
  ShapeModels models;  // after `shape`: an instance goes before the topology it was made on
  // What it was prepared against (still_fits).
  const BodyTopology* prepared_on = nullptr;
  const ModelInstance* model_then = nullptr;
  size_t next_swap_then = 0;
};

// Throws InputError (nothing changed) when the body cannot be cut: cut_unsupported, a model swap
// waiting, what cut_mesh refuses, velocities not matching the positions. Allocates; reads nothing
// a tick writes but `positions` and `velocities`.
PreparedCut prepare_cut(World& world, size_t slot, std::span<const double> triangles, CutMode mode,
                        std::span<const double> positions, std::span<const double> velocities);

// Whether body cut.slot still has the mesh and model `cut` was prepared on (no other cut, no model
// swap since): else it must be prepared again.
bool still_fits(const World& world, const PreparedCut& cut) noexcept;

// The second half, at a tick boundary at simulated `time` (s): the arrays filled from the body's
// state now, the shape exchanged, the totals counted, the new model begun (the energies are
// reckoned in prepare_cut and retire_cut, off the tick). The body's mesh must be the one `cut`
// was prepared on (still_fits). Allocates nothing.
CutSummary apply_cut(World& world, PreparedCut& cut, double time) noexcept;

// Books the energy an applied cut took (CutTotals::removed_energy_J: the old model's kinetic +
// elastic energy at the state the cut was asked at, less the new one's) and keeps what it
// replaced (RetiredArrays: views handed out stay readable). Allocates; off the tick.
void retire_cut(World& world, PreparedCut& cut);

}  // namespace tacta
