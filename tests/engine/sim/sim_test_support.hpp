// Test support for whole-simulation tests: one plugin registry per test program (the build
// tree's real plugins plus this folder's test plugins), scenes from text, a CSV reader, and a
// World + HapticLoop harness that drives the 1 kHz task tick by tick as Simulation::run does.
#pragma once

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "collision/collision_context.hpp"
#include "haptic_interaction/haptic_interaction.hpp"
#include "systems/haptic_loop.hpp"
#include "tacta/plugin_registry.hpp"
#include "tacta/scene_loader.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "tacta/sim/simulation.hpp"
#include "world/world.hpp"

namespace tacta::simtest {

// The registry is loaded once per program: dlopen of every plugin is the slow part.
inline const PluginRegistry& plugins() {
  static const std::unique_ptr<PluginRegistry> registry = [] {
    auto r = std::make_unique<PluginRegistry>();
    r->load();
    r->add_path(TACTA_SIM_TEST_PLUGIN_DIR);
    r->load();
    return r;
  }();
  return *registry;
}

inline const SchemaLookup& schemas() {
  static const RegistrySchemas lookup(plugins());
  return lookup;
}

// A scene from text, named as if it were the file scenes/<name>.yaml of the source tree (so a
// relative mesh path such as ../assets/meshes/liver.msh resolves).
inline std::string scene_path(const std::string& name) {
  return std::string(TACTA_SOURCE_DIR) + "/scenes/" + name + ".yaml";
}
inline SceneDesc scene_from_text(const std::string& text, const std::string& name,
                                 const std::vector<std::string>& overrides = {}) {
  return load_scene_from_string(text, scene_path(name), schemas(), overrides);
}

// A fresh, empty folder under the test temp dir.
inline std::string fresh_dir(const std::string& name) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("tacta_simtest_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

// A checkpoint of `scene` after `ticks` lockstep ticks, from a Simulation closed after it.
inline std::vector<uint8_t> checkpoint_after(const SceneDesc& scene, uint64_t ticks) {
  Simulation first(scene, plugins());
  first.step(ticks);
  return first.save_state();
}

inline RunResult run_scene(const SceneDesc& scene, const RunOptions& options = {}) {
  Simulation simulation(scene, plugins());
  return simulation.run(options);
}

// A comma-separated file with a header line, cells kept as text (compare printed values exactly)
// and parsed on demand.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
  size_t column(const std::string& name) const {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
  double number(size_t row, const std::string& name) const {
    return std::stod(rows[row][column(name)]);
  }
};

inline Csv read_csv(const std::string& path) {
  Csv csv;
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "cannot read " << path;
  std::string line;
  bool first = true;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(cell);
    if (first)
      csv.header = cells;
    else
      csv.rows.push_back(cells);
    first = false;
  }
  return csv;
}

// A realtime run of `duration_s` on its own thread, followed from the test's thread: the
// simulated time of the last frame the render task handed over, and a wait for it to pass a
// time (requests posted while the run goes on).
class RealtimeRun final : public FrameObserver {
 public:
  RealtimeRun(Simulation& simulation, double duration_s) {
    RunOptions options;
    options.realtime = true;
    options.duration_s = duration_s;
    options.observers.push_back(this);
    runner_ = std::thread([this, &simulation, options] { result_ = simulation.run(options); });
  }
  ~RealtimeRun() override {
    if (runner_.joinable()) runner_.join();
  }
  void on_frame(const SceneStatic&, const Snapshot& s) override { time_.store(s.time_s); }
  void wait_until(double t) const {
    while (time_.load() < t) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  const RunResult& join() {
    runner_.join();
    return result_;
  }

 private:
  std::atomic<double> time_{0};
  RunResult result_;
  std::thread runner_;
};

// A 0.3 m beam clamped at x = 0, sagging under gravity (corotational FEM, 0.2 s).
inline const char* const kSaggingBeamScene = R"(
name: beam_stepping
gravity: [0, -9.81, 0]
clock: {duration_s: 0.2}
bodies:
  - name: beam
    mesh: {beam_grid: {size: [0.3, 0.04, 0.04], cells: [6, 1, 1]}}
    material: {youngs_modulus: 2.0e6, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 1.0}
    model: corotational_fem
    fixed: [{box: {min: [-0.001, -1, -1], max: [0.001, 1, 1]}}]
)";

// The 1 kHz task without the scheduler: the same objects Simulation::run wires together.
class LoopHarness {
 public:
  explicit LoopHarness(const SceneDesc& scene, size_t ticks)
      : world(scene, plugins()),
        collision(world, plugins()),
        haptics(world, collision),
        snapshots(HapticLoop::make_prototype(world)),
        loop(world, snapshots, ticks),
        dt(1.0 / scene.clock.haptic_rate_hz) {
    for (size_t i = 0; i < world.body_count(); ++i) {
      const SoftBody b = world.body(i);
      b.model.instance->begin(b.state_view(0.0), dt);
    }
    loop.set_haptics(&haptics);
  }
  void tick() {
    loop.tick(next, static_cast<double>(next) * dt, dt);
    ++next;
  }

  World world;
  CollisionContext collision;
  HapticInteraction haptics;
  TripleBuffer<Snapshot> snapshots;
  HapticLoop loop;
  double dt;
  uint64_t next = 0;
};

// A soft cube on a table, pressed from above by the simulated stylus following waypoints
// (t x y z): from 11 mm above the top face down to 8 mm into it over 0.15 s, then held.
inline const char* const kCubePressScene = R"(
name: cube_press
gravity: [0, -9.81, 0]
seed: 3
clock: {mode: lockstep, haptic_rate_hz: 1000, render_rate_hz: 60, duration_s: 0.4}
bodies:
  - name: cube
    mesh: {box_grid: {size: [0.1, 0.1, 0.1], cells: [3, 3, 3], origin: [-0.05, 0, -0.05]}}
    material: {youngs_modulus: 2.0e4, poisson_ratio: 0.4, density: 1000, rayleigh_mass: 2.0}
    model: tensor_mass
    fixed: [{box: {min: [-1, -0.001, -1], max: [1, 0.001, 1]}}]
devices:
  - name: stylus
    plugin: sim_stylus
    params:
      workspace_origin: [0, 0.1, 0]
      pattern: waypoints
      waypoints: [0, 0.011, 0.115, 0.007,   0.15, 0.011, 0.092, 0.007]
    tool: {sphere: {radius: 0.004}}
    coupling: {stiffness: 400, damping: 1.0}
    touches: cube
collision: {broad_phase: bvh}   # answers the proxy's surface queries
)";

}  // namespace tacta::simtest
