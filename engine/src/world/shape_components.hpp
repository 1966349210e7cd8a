// The components of the scene's rigid things: the tool each device carries and the static
// obstacles (colliders). Each is an entity of the World's registry, made at load; the collision
// plugins see their shapes through CollisionContext's packed view.
#pragma once

#include <cstdint>
#include <vector>

#include "tacta/collision_api.h"
#include "tacta/scene.hpp"

namespace tacta {

// A rigid shape as the collision plugins see it, and the hull points it points into (the vector's
// buffer, which moves with the component without being reallocated).
struct RigidShape {
  tacta_collision_shape shape{};
  std::vector<double> hull_points;  // m, 3 per point, local frame; empty unless a hull
};

// A static obstacle of the scene (`obstacles`): plane, box, sphere, capsule or convex hull.
struct Collider {
  RigidShape rigid;
};

// The shape a device carries into the scene (`devices[].tool`); its pose follows the device's
// proxy each tick (HapticInteraction).
// A tool's blade (ShapeDesc::blade) and what its edge swept since the last cut: the tick adds
// two triangles a tick while the button is held (no allocation: `swept` is reserved when the tool
// is built); the cut itself is made between ticks (Simulation's lockstep cuts).
struct BladeSweep {
  static constexpr size_t kCapacityTriangles = 4096;  // 2 s of sweeping at 1 kHz
  bool enabled = false;
  BladeDesc desc;
  bool held = false;           // the button was down at the last tick
  std::array<Vec3, 2> last{};  // the edge's ends at the last tick, m, world
  std::vector<double> swept;   // 9 per triangle, m, world
  double first_s = -1;         // s: when the oldest triangle in `swept` was added; -1: none
  bool released = false;       // the button was let go since the last cut
  uint64_t dropped = 0;        // triangles past the capacity since the last cut, never cut
};

struct Tool {
  RigidShape rigid;
  uint32_t device = 0;      // index in the scene's devices
  double proxy_radius = 0;  // m: the haptic proxy's sphere (the shape's `radius`)
  uint32_t revision = 0;    // tools changed while the scene ran (report: tool_changes)
  BladeSweep blade;
};

// A tool built to replace a device's while the scene runs (World::change_tool, a scene event).
Tool build_tool(const ShapeDesc& desc, uint32_t id, uint32_t device);

// Builds the shape from its scene description with collision id `id` (a mesh becomes the hull
// of its points). Throws InputError (missing or unreadable mesh file).
RigidShape build_rigid_shape(const ShapeDesc& desc, uint32_t id);

}  // namespace tacta
