// The bodies' and devices' part of a checkpoint: per body its evolving state (nodes, loads,
// presence, model in use with its parameters and own state, step progress, fault, boundary
// motion); per device its sample, connection, contact, statistics and the plugin's own state.
// What the scene fixes (mesh, material, schedule, limits) is not saved: the restoring
// Simulation builds it from the same scene, which the fingerprint checks; a body's mesh is saved
// once a cut changed it (checkpoint/shape_state.hpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "checkpoint/checkpoint_format.hpp"
#include "tacta/param_set.hpp"
#include "tacta/scene.hpp"
#include "world/world.hpp"

namespace tacta {

// What the scene is, for refusing a checkpoint of another: name, rates, seed, and per body
// and device the names, counts, models and parameters (so --set overrides count).
uint64_t scene_fingerprint(const World& world);

// The model each body was last asked for (Simulation's requested_models/params).
struct RequestedModels {
  std::vector<std::string>& models;
  std::vector<ParamSet>& params;
};

// Throws InputError naming the body when it cannot be saved (a model with no state entries and
// no NO_HISTORY claim, a body on its own thread, a swap still waiting).
void save_bodies(CheckpointWriter& out, World& world, const RequestedModels& requested);
// Returns the bodies given another shape (a cut one, or the scene's again): their collision
// surface, proxies and render description must follow.
std::vector<size_t> load_bodies(CheckpointReader& in, World& world, const PluginRegistry& plugins,
                                const RequestedModels& requested);
// Returns a note per device that cannot carry its state (a live link: it reconnects).
std::vector<std::string> save_devices(CheckpointWriter& out, World& world);
std::vector<std::string> load_devices(CheckpointReader& in, World& world);

}  // namespace tacta
