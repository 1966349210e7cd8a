// What the haptic task publishes for the render task at each frame: copies of the state, made
// into buffers sized at load time (no allocation in the 1 kHz path).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace tacta {

struct BodySnapshot {
  std::vector<double> positions;          // 3 per node, m
  std::vector<double> velocities;         // 3 per node, m/s
  std::vector<double> von_mises;          // 1 per node, Pa (empty when the model gives no stress)
  std::vector<double> surface_positions;  // 3 per embedded surface vertex, m (empty: none)
  std::string model;  // model name at the time of the snapshot (set at swaps only)
  bool frozen = false;
  bool present = true;    // false while an added body waits for its time, and after it was removed
  uint32_t revision = 0;  // the mesh revision (BodyStatic::revision) the arrays above follow
  double kinetic_J = 0, elastic_J = 0, max_displacement_m = 0;
};

struct DeviceSnapshot {
  std::array<double, 3> position{};  // m
  std::array<double, 3> proxy{};     // m
  std::array<double, 3> force{};     // N, as sent to the device
  bool contact = false;
  int touched_body = -1;  // index of the body it touches, -1 when none
};

struct Snapshot {
  double time_s = 0;
  uint64_t tick = 0;
  double last_tick_ms = 0;
  std::vector<BodySnapshot> bodies;
  std::vector<DeviceSnapshot> devices;
};

// What does not change during a run, for whoever draws or saves snapshots.
struct BodyStatic {
  std::string name;
  std::vector<double> rest_positions;  // 3 per node, m
  std::vector<uint32_t> triangles;     // 3 per triangle: the surface to draw (outward)
  std::vector<uint32_t> tets;          // 4 per tet (VTK output)
  std::vector<uint32_t> quads;         // 4 per quad (planar meshes)
  std::vector<uint32_t> fixed_nodes;   // indices of the fixed nodes
  uint32_t dimension = 3;
  // The embedded surface (tacta/embedded_surface.hpp), drawn instead of `triangles` when present.
  std::vector<double> surface_rest_positions;  // 3 per surface vertex, m
  std::vector<uint32_t> surface_triangles;     // 3 per triangle (outward)
  // Cuts: the mesh's revision (0: as loaded; each cut that changed it adds 1, and every array
  // above is then the new mesh's), and per triangle of `triangles` / `surface_triangles` 1 when a
  // cut exposed it (empty when never cut).
  uint32_t revision = 0;
  std::vector<uint8_t> cut_triangles;
  std::vector<uint8_t> surface_cut_triangles;
};

struct DeviceStatic {
  std::string name;
  double tool_radius_m = 0.002;
  double peak_force_N = 0;
};

struct SceneStatic {
  std::string name;
  std::vector<BodyStatic> bodies;
  std::vector<DeviceStatic> devices;
  double haptic_rate_hz = 1000;
};

// Receives each new snapshot on the render task's thread (the haptic thread never waits for it).
class FrameObserver {
 public:
  virtual ~FrameObserver() = default;
  virtual void on_start(const SceneStatic& /*scene*/) {}
  virtual void on_frame(const SceneStatic& scene, const Snapshot& snapshot) = 0;
  // Called after the run on the calling thread: files written, for the report's output list.
  virtual std::vector<std::string> finish() { return {}; }
};

}  // namespace tacta
