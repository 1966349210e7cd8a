// The SoftBody component: a deformable body's node state, rest state, masses, fixed nodes, the
// forces acting on it this tick, and the model instance that advances it. The engine owns the
// state arrays so that a body can change model mid-run; the model sees them as plain spans.
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "boundary_motion.hpp"
#include "plugin_instance.hpp"
#include "probes.hpp"
#include "tacta/embedded_surface.hpp"
#include "tacta/mesh.hpp"
#include "tacta/mesh_io.hpp"
#include "tacta/model_api.h"
#include "tacta/scene.hpp"

namespace tacta {

// What a model instance points into for its whole life; heap-held so it never moves even when
// the component pool that holds the SoftBody grows.
struct BodyTopology {
  VolumeMesh mesh;
  tacta_mesh_view view{};
  tacta_material material{};
  std::vector<double> masses;  // kg per node, lumped
  std::vector<uint8_t> fixed;  // 1 per node
  LoadReport load;             // what the mesh file became (voxels, Gmsh tets) and its warnings
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

struct BodyFault {
  bool frozen = false;
  uint32_t bits = 0;               // TACTA_STEP_* bits of the step that failed
  double time_s = 0;               // simulated time of the failed step
  std::array<char, 160> reason{};  // fixed buffer: written from the 1 kHz path
};

// When a body is part of the running scene. Bodies added while a scene runs wait as Pending
// until the tick boundary that takes them in; removed ones stay (frozen in place, out of every
// system) so the report still lists them.
struct BodyPresence {
  enum State : uint8_t { kPending, kPresent, kRemoved };
  State state = kPresent;
  double added_s = -1;          // s, simulated; -1: in the scene from the start
  double removed_s = -1;        // s, simulated; -1: not removed
  double initial_energy_J = 0;  // kinetic + elastic when added (bodies added while running)
};

struct SoftBody {
  std::string name;
  BodyPresence presence;
  std::string load_warning;  // something odd but legal in the scene (every node fixed); empty: none
  std::unique_ptr<BodyTopology> topology;
  // The surface the body is drawn, touched and collided through when it came from a surface file
  // or was given `surface:`; null: the boundary triangles of its tets. Heap-held: views point in.
  std::unique_ptr<EmbeddedSurface> surface;
  std::vector<double> positions;   // 3 per node, m
  std::vector<double> velocities;  // 3 per node, m/s
  std::vector<double>
      external_forces;                 // 3 per node, N: gravity + contact + tool, rebuilt each tick
  std::vector<double> contact_forces;  // 3 per node, N: accumulated by collision/haptics this tick
  std::vector<double> saved_positions;  // start of the tick, restored when the body is frozen
  std::vector<double> applied_forces;   // 3 per node, N, set through the stepping API; empty: none
  std::unique_ptr<ModelInstance> model;
  std::vector<ScheduledSwap> swaps;  // sorted by time
  size_t next_swap = 0;
  std::string initial_model;  // the scene's model; later ones are in swaps/runtime_swaps
  std::unique_ptr<ModelMailbox> mailbox = std::make_unique<ModelMailbox>();
  std::vector<RuntimeSwap> runtime_swaps;  // reserved at load; swaps past its capacity go unlisted
  uint64_t runtime_swaps_unlisted = 0;     // and are counted here (report.json models_run_unlisted)
  BodyFault fault;
  double divergence_limit_m = 1;  // displacement beyond which the body counts as diverged
  double max_displacement_m = 0;  // over the whole run
  std::optional<uint32_t> probe_node;
  std::vector<uint32_t> recorded_nodes;      // nodes whose trajectory is recorded
  std::vector<Probe> probes;                 // rest points followed through their tets (probes.csv)
  std::unique_ptr<BoundaryMotion> boundary;  // prescribed motion and plates; null when none
  double step_period_s = 0;                  // s; 0: every haptic tick
  double next_step_time_s = 0;               // s; when a slower body steps next
  bool own_thread = false;                   // steps on a BodyWorker thread, not the haptic one
  uint64_t refreshes = 0;  // own_thread: finished steps taken into the arrays above so far
  bool local_contact_yielding = true;  // own_thread: render through haptics::LocalCompliance

  bool present() const noexcept { return presence.state == BodyPresence::kPresent; }
  size_t node_count() const { return positions.size() / 3; }
  // s: how far one model step advances this body (its own step period, else the haptic tick).
  double step_dt(double haptic_dt) const noexcept {
    return step_period_s > 0 ? step_period_s : haptic_dt;
  }
  const std::vector<double>& rest() const { return topology->mesh.positions; }
  double kinetic_energy() const noexcept;
  tacta_body_state state_view(double time) noexcept {
    return {static_cast<uint32_t>(node_count()), positions.data(), velocities.data(),
            external_forces.data(), time};
  }
};

class PluginRegistry;

// Resolves a model plugin by name and builds its instance for this body. Throws InputError.
using ModelFactory = std::function<std::unique_ptr<ModelInstance>(
    const std::string& model, const ParamSet& params, const BodyTopology& topology, double dt,
    const SourceLocation& where)>;

// Builds the body from its scene description (mesh, masses, fixed nodes, initial state, model,
// scheduled swaps). Throws InputError; never returns a half-built body.
SoftBody build_soft_body(const BodyDesc& desc, const SceneDesc& scene,
                         const ModelFactory& make_model);

}  // namespace tacta
