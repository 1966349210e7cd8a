#include "tacta/sim/simulation.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "../report/run_outputs.hpp"
#include "collision_context.hpp"
#include "haptic_interaction.hpp"
#include "haptic_loop.hpp"
#include "world.hpp"

namespace tacta {

namespace {

// Takes the newest snapshot at each frame. Frames (PNG) and VTK output hook in here.
class OutputRenderTask final : public RenderTask {
 public:
  explicit OutputRenderTask(TripleBuffer<Snapshot>& snapshots) : snapshots_(snapshots) {}
  void frame(double /*wall_time*/) override {
    if (snapshots_.acquire()) ++frames_seen_;
  }
  uint64_t frames_seen() const { return frames_seen_; }

 private:
  TripleBuffer<Snapshot>& snapshots_;
  uint64_t frames_seen_ = 0;
};

void print_progress(double fraction) {
  const int width = 40;
  const int filled = static_cast<int>(fraction * width + 0.5);
  std::fprintf(stderr, "\r[%.*s%*s] %3d%%", filled, "########################################", width - filled, "",
               static_cast<int>(fraction * 100 + 0.5));
  std::fflush(stderr);
}

size_t element_count(const VolumeMesh& m) {
  return m.tets.size() / 4 + m.quads.size() / 4 + (m.dimension == 2 && m.quads.empty() ? m.triangles.size() / 3 : 0);
}

}  // namespace

std::string hash_positions(const std::vector<const std::vector<double>*>& arrays) {
  uint64_t h = 1469598103934665603ull;  // FNV-1a 64 offset basis
  for (const std::vector<double>* a : arrays) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(a->data());
    for (size_t i = 0; i < a->size() * sizeof(double); ++i) {
      h ^= bytes[i];
      h *= 1099511628211ull;  // FNV-1a 64 prime
    }
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

struct Simulation::Impl {
  Impl(const SceneDesc& scene, const PluginRegistry& plugins) : world(scene, plugins) {
    // Collision is needed for contact response, and for the haptic proxy's surface queries.
    if (scene.collision.enabled || world.device_count() > 0) {
      collision = std::make_unique<CollisionContext>(world, plugins);
      if (world.device_count() > 0) haptics = std::make_unique<HapticInteraction>(world, *collision);
      if (scene.collision.enabled) response = std::make_unique<CollisionResponse>(*collision);
    }
  }
  World world;
  std::unique_ptr<CollisionContext> collision;
  std::unique_ptr<HapticInteraction> haptics;
  std::unique_ptr<CollisionResponse> response;
};

Simulation::Simulation(const SceneDesc& scene, const PluginRegistry& plugins)
    : impl_(std::make_unique<Impl>(scene, plugins)) {}

Simulation::~Simulation() = default;

RunResult Simulation::run(const RunOptions& options) {
  World& world = impl_->world;
  const SceneDesc& scene = world.scene();
  ScheduleOptions schedule;
  schedule.mode = scene.clock.mode == ClockDesc::Mode::Realtime ? ClockMode::Realtime : ClockMode::Lockstep;
  if (options.realtime) schedule.mode = *options.realtime ? ClockMode::Realtime : ClockMode::Lockstep;
  schedule.haptic_rate_hz = scene.clock.haptic_rate_hz;
  schedule.render_rate_hz = scene.clock.render_rate_hz;
  schedule.duration_s = options.duration_s.value_or(scene.clock.duration_s);
  if (options.progress) schedule.on_progress = print_progress;

  RunResult result;
  result.scene = scene.path;
  result.mode = schedule.mode == ClockMode::Realtime ? "realtime" : "lockstep";
  for (size_t i = 0; i < world.body_count(); ++i) {
    SoftBody& b = world.body(i);
    BodyResult br;
    br.initial_energy_J = b.kinetic_energy() + b.model->elastic_energy(b.positions.data());
    result.bodies.push_back(br);
    const tacta_body_state state = b.state_view(0.0);
    b.model->begin(state, b.step_period_s > 0 ? b.step_period_s : 1.0 / schedule.haptic_rate_hz);
  }

  const auto expected_ticks = static_cast<size_t>(schedule.duration_s * schedule.haptic_rate_hz + 1);
  TripleBuffer<Snapshot> snapshots(HapticLoop::make_prototype(world));
  HapticLoop loop(world, snapshots, expected_ticks);
  if (!options.record_log.empty()) {
    if (world.device_count() == 0) throw InputError({scene.path, 0, 0, "devices"}, "--record: the scene has no device to record");
    loop.enable_device_log(expected_ticks);
  }
  if (impl_->haptics) loop.add_interaction(impl_->haptics.get());
  if (impl_->response) loop.add_interaction(impl_->response.get());
  OutputRenderTask render(snapshots);
  result.schedule = run_schedule(loop, render, schedule);
  if (options.progress) std::fprintf(stderr, "\n");
  result.sim_time_s = static_cast<double>(result.schedule.ticks) / schedule.haptic_rate_hz;

  std::vector<const std::vector<double>*> arrays;
  for (size_t i = 0; i < world.body_count(); ++i) {
    const SoftBody& b = world.body(i);
    BodyResult& br = result.bodies[i];
    br.name = b.name;
    br.model = b.model->name();
    br.nodes = b.node_count();
    br.fixed_nodes = static_cast<size_t>(std::count(b.topology->fixed.begin(), b.topology->fixed.end(), 1));
    br.elements = element_count(b.topology->mesh);
    br.max_displacement_m = b.max_displacement_m;
    br.kinetic_energy_J = b.kinetic_energy();
    br.elastic_energy_J = b.model->elastic_energy(b.positions.data());
    br.frozen = b.fault.frozen;
    if (b.fault.frozen) br.fault = b.fault.reason.data();
    arrays.push_back(&b.positions);
  }
  result.state_hash = hash_positions(arrays);
  result.faults = loop.faults().rows().size();
  result.exit_code = result.faults > 0 ? 1 : 0;

  if (loop.device_log() != nullptr) {
    std::filesystem::path log(options.record_log);
    if (log.has_parent_path()) std::filesystem::create_directories(log.parent_path());
    loop.device_log()->write_csv(options.record_log);
    result.outputs.push_back(options.record_log);
  }
  if (!options.out_dir.empty()) {
    std::filesystem::create_directories(options.out_dir);
    write_csv_records(options.out_dir, loop, world, result);
    std::vector<std::string> warnings;
    write_plots(options.out_dir, world, result, warnings);
    for (const std::string& w : warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
    write_report_json(options.out_dir, loop, world, result);
  }
  return result;
}

}  // namespace tacta
