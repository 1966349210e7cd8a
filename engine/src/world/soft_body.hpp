// A deformable body as a set of components (body_components.hpp): BodyParts holds them by value
// (what building a body makes, before the World moves it into its registry pools); SoftBody
// holds references to one body's components in the pools, for code that needs the whole body
// (building, the report, snapshots, the stepping API). The tick's systems take views instead.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <string>

#include "tacta/scene.hpp"
#include "world/body_components.hpp"

namespace tacta {

struct BodyParts {
  BodyInfo info;
  BodyPresence presence;
  NodeState nodes;
  NodeLoads loads;
  RestShape shape;
  BodySurface surface;
  BodyModel model;
  BodySettings settings;
  StepProgress progress;
  BodyConstraints constraints;
  FaultState fault;
  Recording recording;
};

// What a model's begin and step see of a body at `time` (s): its node arrays, in place.
inline tacta_body_state state_view(NodeState& nodes, NodeLoads& loads, double time) noexcept {
  return {static_cast<uint32_t>(nodes.node_count()), nodes.positions.data(),
          nodes.velocities.data(), loads.external_forces.data(), time};
}

struct SoftBody {
  BodyInfo& info;
  BodyPresence& presence;
  NodeState& nodes;
  NodeLoads& loads;
  RestShape& shape;
  BodySurface& surface;
  BodyModel& model;
  const BodySettings& settings;
  StepProgress& progress;
  BodyConstraints& constraints;
  FaultState& fault;
  Recording& recording;

  bool present() const noexcept { return presence.present(); }
  size_t node_count() const noexcept { return nodes.node_count(); }
  double step_dt(double haptic_dt) const noexcept { return settings.step_dt(haptic_dt); }
  const std::vector<double>& rest() const { return shape.rest(); }
  double kinetic_energy() const noexcept;
  tacta_body_state state_view(double time) const noexcept {
    return tacta::state_view(nodes, loads, time);
  }
};

// Starts the body's model at `time` (s) for steps of its own period or the haptic tick
// (model.begin) and returns its mechanical energy just before, kinetic + elastic (J): the
// reference the energy records compare with.
double begin_model(const SoftBody& body, double time, double haptic_dt) noexcept;

// J: ½ Σ m v² over the nodes (lumped masses).
double kinetic_energy(const NodeState& nodes, const BodyTopology& topology) noexcept;
// The same from the arrays: `masses` 1 per node (kg), `velocities` 3 per node (m/s).
double kinetic_energy(std::span<const double> masses, std::span<const double> velocities) noexcept;

// The plugin view of a mesh: pointers into its arrays (valid while the mesh lives, unmoved).
tacta_mesh_view make_view(const VolumeMesh& mesh);

// Resolves a model plugin by name and builds its instance for this body. Throws InputError.
using ModelFactory = std::function<std::unique_ptr<ModelInstance>(
    const std::string& model, const ParamSet& params, const BodyTopology& topology, double dt,
    const SourceLocation& where)>;

// Builds the body from its scene description (mesh, masses, fixed nodes, initial state, model,
// scheduled swaps). Throws InputError; never returns a half-built body.
BodyParts build_soft_body(const BodyDesc& desc, const SceneDesc& scene,
                          const ModelFactory& make_model);

}  // namespace tacta
