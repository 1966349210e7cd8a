// The scene loader's section readers; each validates one part of the YAML tree completely.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "scene/yaml_field.hpp"
#include "tacta/scene.hpp"

namespace tacta::scene_detail {

MaterialDesc read_material(const Field& field);
MeshSourceDesc read_mesh_source(const Field& field);
BodyDesc read_body(const Field& field);

// A cut's `mode`: remove | separate.
CutMode read_cut_mode(const Field& field);

// A device's tool (`tool`: true) may carry a blade; an obstacle's shape may not.
ShapeDesc read_shape(const Field& field, bool tool = false);
DeviceDesc read_device(const Field& field, const std::vector<BodyDesc>& bodies);
ObstacleDesc read_obstacle(const Field& field);
CollisionDesc read_collision(const Field& field);
SwapDesc read_swap(const Field& field, const std::vector<BodyDesc>& bodies);

ClockDesc read_clock(const Field& field);
OutputDesc read_output(const Field& field);

// Node count of a grid primitive (known before the mesh is built), nullopt for files and spheres.
std::optional<uint64_t> grid_node_count(const MeshSourceDesc& mesh);

// Node selections: an index (checked against a grid's node count when known), a non-empty list
// of them, and a region {box: {min, max}} or {nodes: [...]}.
uint32_t read_node(const Field& field, std::optional<uint64_t> node_count);
std::vector<uint32_t> read_nodes(const Field& field, std::optional<uint64_t> node_count);
FixedRegionDesc read_fixed_region(const Field& field, std::optional<uint64_t> node_count);

// A body's `prescribed`, `plates` and `probes` (boundary_reader.cpp).
void read_boundary(const Field& body_field, BodyDesc& body, std::optional<uint64_t> node_count);

// The one key of `allowed` that `field` (a map) holds; fails when it holds none or several.
std::string exactly_one_of(const Field& field, const std::vector<std::string>& allowed);

// Fails on the second of two items with one name (bodies, devices, obstacles).
void check_unique(const std::vector<Field>& items, const std::vector<std::string>& names,
                  const char* what);

// The scene's `events` (event_reader.cpp), after its bodies and devices are read; `body_items`
// are the fields of scene.bodies.
void read_events(const Field& field, const std::vector<Field>& body_items, SceneDesc& scene);

}  // namespace tacta::scene_detail
