// The components of a body entity, one concern each. They live in the World's registry pools
// (reserved at load for every body slot, never removed: a removed body's last state stays for the
// report) and the systems (body_systems.hpp) run over views of them. Plain structs; the arrays
// are 3 doubles per node.
#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "boundary/boundary_motion.hpp"
#include "boundary/probes.hpp"
#include "plugin/plugin_instance.hpp"
#include "tacta/ecs.hpp"
#include "tacta/embedded_surface.hpp"
#include "tacta/mesh.hpp"
#include "tacta/mesh_io.hpp"
#include "tacta/model_api.h"

namespace tacta {

// What a model instance points into for its whole life; heap-held so it never moves.
struct BodyTopology {
  VolumeMesh mesh;
  tacta_mesh_view view{};
  tacta_material material{};
  std::vector<double> masses;  // kg per node, lumped
  std::vector<uint8_t> fixed;  // 1 per node
  LoadReport load;             // what the mesh file became (voxels, Gmsh tets) and its warnings
};

struct BodyInfo {
  std::string name;
  std::string load_warning;  // something odd but legal in the scene (every node fixed); empty: none
};

// Tag: the body is in the running scene (entered, not removed). Systems view bodies through it.
struct InScene {};

// When a body is part of the running scene. Bodies added while a scene runs wait as Pending
// until the tick boundary that takes them in; removed ones stay (frozen in place, out of every
// system) so the report still lists them.
struct BodyPresence {
  enum State : uint8_t { kPending, kPresent, kRemoved };
  State state = kPresent;
  double added_s = -1;          // s, simulated; -1: in the scene from the start
  double removed_s = -1;        // s, simulated; -1: not removed
  double initial_energy_J = 0;  // kinetic + elastic when added (bodies added while running)

  bool present() const noexcept { return state == kPresent; }
};

struct NodeState {
  std::vector<double> positions;   // m
  std::vector<double> velocities;  // m/s
  // m: where the last step started. A faulted step is put back here; collision sweeps and the
  // haptic proxy move from here to `positions`.
  std::vector<double> step_start;
  size_t node_count() const noexcept { return positions.size() / 3; }
};

struct NodeLoads {
  std::vector<double> external_forces;  // N: gravity + contact + tool, rebuilt each step
  std::vector<double> contact_forces;   // N: accumulated by collision and haptics this tick
  std::vector<double> applied_forces;   // N, set through the stepping API; empty: none
};

// What the cuts so far did to a body (world/body_cut.hpp).
struct CutTotals {
  uint32_t revision = 0;  // cuts that changed the mesh; 0: the mesh the scene loaded
  uint64_t tets_removed = 0, nodes_removed = 0, nodes_added = 0, faces_separated = 0;
  uint64_t cuts_missed = 0;     // blades that met no tet
  double removed_mass_kg = 0;   // removal: the mass the removed tets carried
  double removed_energy_J = 0;  // kinetic + elastic the removed material took with it
  // Wall time of the cuts made, ms, from the request to the new mesh in place: in lockstep the
  // edit and every rebuild, which the tick after waits for; in a realtime run the worker's time
  // too, while the ticks went on.
  double wall_ms_total = 0, wall_ms_max = 0;
};

// A body's arrays from before a cut, kept until the World closes: pointers the stepping API handed
// out (BodyArrays, Python's array views) stay readable, holding the state at the cut.
struct RetiredArrays {
  std::unique_ptr<BodyTopology> topology;
  std::vector<double> positions, velocities;
  std::unique_ptr<EmbeddedSurface> surface;  // the embedded surface before (null: none)
  std::unique_ptr<BoundaryMotion> boundary;  // the boundary motion before (null: none)
};

struct RestShape {
  std::unique_ptr<BodyTopology> topology;
  std::vector<RetiredArrays> retired;  // one per cut that changed the mesh
  // Faces a blade crossed that have not opened yet (sorted node triples): the next cut counts them
  // crossed again, so an incision made in strokes opens as its faces' nodes are severed.
  std::vector<std::array<uint32_t, 3>> crack;
  // Per boundary triangle of topology->mesh: 1 when a cut exposed it (drawn in the cut colour);
  // empty while the body was never cut.
  std::vector<uint8_t> cut_triangles;
  // Per node: the node of the mesh the scene loaded that it is a copy of (empty while never cut),
  // for what the scene set per node (prescribed motion, plates).
  std::vector<uint32_t> loaded_node;
  CutTotals cuts;             // checkpointed as it is: add no field
  double install_ms_max = 0;  // realtime runs: the longest a tick boundary spent installing a cut
  const std::vector<double>& rest() const { return topology->mesh.positions; }
  // The topology the scene loaded (before any cut), which checkpoints fingerprint.
  const BodyTopology& loaded() const {
    return retired.empty() ? *topology : *retired.front().topology;
  }
};

// The embedded surface entity of a body slot (made at load, one per slot): the surface the body
// is drawn, touched and collided through when it came from a surface file or was given
// `surface:`. `mesh` null: the body is seen through its tets' boundary. Heap-held: views point in.
struct BodySurface {
  std::unique_ptr<EmbeddedSurface> mesh;
  uint32_t body = 0;  // the body slot it follows
};

// On a body entity: its embedded surface's entity.
struct SurfaceLink {
  ecs::Entity surface;
};

// A model change scheduled for a time, built at load time so the switch itself allocates nothing.
struct ScheduledSwap {
  double time_s = 0;
  std::string model_name;                // the incoming model, for the report
  std::unique_ptr<ModelInstance> model;  // incoming until the swap; the outgoing one after it
};

// Runtime swaps requested from another thread (the viewer): the requester builds the instance
// and posts it in `incoming`; the haptic thread takes it at the start of a tick and pushes the
// outgoing instance on the `retired` stack (lock-free), which the requester empties and deletes.
// The haptic thread never allocates or frees a model.
struct ModelMailbox {
  std::atomic<ModelInstance*> incoming{nullptr};
  std::atomic<ModelInstance*> retired{nullptr};
  ~ModelMailbox();
};

struct RuntimeSwap {
  double time_s;
  const char* model;  // the descriptor's name: lives as long as the plugin registry
};

struct BodyModel {
  std::unique_ptr<ModelInstance> instance;
  std::vector<ScheduledSwap> swaps;  // sorted by time
  size_t next_swap = 0;
  std::string initial_model;  // the scene's model; later ones are in swaps/runtime_swaps
  std::unique_ptr<ModelMailbox> mailbox = std::make_unique<ModelMailbox>();
  std::vector<RuntimeSwap> runtime_swaps;  // reserved at load; swaps past its capacity go unlisted
  uint64_t runtime_swaps_unlisted = 0;     // and are counted here (report.json models_run_unlisted)
};

// The body's settings: what the scene fixed at load and no tick changes (MuJoCo's mjModel side).
// Everything the ticks change is in the state components (NodeState, NodeLoads, StepProgress,
// FaultState, ...), which are what a checkpoint holds.
struct BodySettings {
  double period_s = 0;                 // s; 0: every haptic tick
  bool own_thread = false;             // steps on a BodyWorker thread, not the haptic one
  bool local_contact_yielding = true;  // own_thread: render through haptics::LocalCompliance
  double divergence_limit_m = 1;       // displacement beyond which the body counts as diverged
  // s: how far one model step advances this body (its own period, else the haptic tick).
  double step_dt(double haptic_dt) const noexcept { return period_s > 0 ? period_s : haptic_dt; }
};

// Where the body's own stepping stands.
struct StepProgress {
  double next_step_s = 0;  // s; when a slower body steps next
  uint64_t refreshes = 0;  // own_thread: finished steps taken into NodeState so far
  double step_wall_ms = 0;  // wall time of its last step on the tick's threads (who goes first)
};

// Prescribed motion and plates; null when none.
struct BodyConstraints {
  std::unique_ptr<BoundaryMotion> boundary;
};

// The divergence watch and, once it fired, the fault that froze the body.
struct FaultState {
  bool frozen = false;
  uint32_t bits = 0;               // TACTA_STEP_* bits of the step that failed
  double time_s = 0;               // simulated time of the failed step
  std::array<char, 160> reason{};  // fixed buffer: written from the 1 kHz path
  double max_displacement_m = 0;   // over the whole run
};

// What is recorded of the body beyond its state: trajectories and probes.
struct Recording {
  std::optional<uint32_t> probe_node;
  std::vector<uint32_t> recorded_nodes;  // nodes whose trajectory is recorded
  std::vector<Probe> probes;             // rest points followed through their tets (probes.csv)
};

}  // namespace tacta
