#include "tacta/sim/simulation.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "../report/run_outputs.hpp"
#include "collision_context.hpp"
#include "device_surface_feed.hpp"
#include "haptic_interaction.hpp"
#include "haptic_loop.hpp"
#include "vtk_observer.hpp"
#include "world.hpp"

namespace tacta {

namespace {

// Takes the newest snapshot at each frame and hands it to the observers (frames, VTK, a window).
class OutputRenderTask final : public RenderTask {
 public:
  OutputRenderTask(TripleBuffer<Snapshot>& snapshots, const SceneStatic& scene, std::vector<FrameObserver*> observers)
      : snapshots_(snapshots), scene_(scene), observers_(std::move(observers)) {}
  void frame(double /*wall_time*/) override {
    if (!snapshots_.acquire()) return;
    for (FrameObserver* o : observers_) o->on_frame(scene_, snapshots_.read_slot());
  }

 private:
  TripleBuffer<Snapshot>& snapshots_;
  const SceneStatic& scene_;
  std::vector<FrameObserver*> observers_;
};

SceneStatic describe(World& world) {
  SceneStatic s;
  s.name = world.scene().name;
  s.haptic_rate_hz = world.scene().clock.haptic_rate_hz;
  for (size_t i = 0; i < world.body_count(); ++i) {
    const SoftBody& b = world.body(i);
    const VolumeMesh& m = b.topology->mesh;
    BodyStatic bs{b.name, m.positions, m.triangles, m.tets, m.quads, {}, m.dimension, {}, {}};
    if (b.surface) {
      bs.surface_rest_positions = b.surface->rest_positions;
      bs.surface_triangles = b.surface->triangles;
    }
    for (uint32_t n = 0; n < b.topology->fixed.size(); ++n)
      if (b.topology->fixed[n]) bs.fixed_nodes.push_back(n);
    s.bodies.push_back(std::move(bs));
  }
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceSlot& slot = world.device(d);
    s.devices.push_back({slot.name, slot.desc.tool.radius, slot.device->capabilities().peak_force});
  }
  return s;
}

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
  std::atomic<bool> stop{false};
  std::vector<std::string> requested_models;  // per body, for body_model()
  std::unique_ptr<CollisionContext> collision;
  std::unique_ptr<HapticInteraction> haptics;
  std::unique_ptr<CollisionResponse> response;
};

Simulation::Simulation(const SceneDesc& scene, const PluginRegistry& plugins)
    : impl_(std::make_unique<Impl>(scene, plugins)) {
  for (const BodyDesc& b : scene.bodies) impl_->requested_models.push_back(b.model);
}

void Simulation::request_model_swap(size_t body, const std::string& model, const ParamSet& params) {
  World& world = impl_->world;
  if (body >= world.body_count())
    throw InputError({world.scene().path, 0, 0, "bodies"}, "no body with index " + std::to_string(body));
  SoftBody& b = world.body(body);
  const double dt = b.step_period_s > 0 ? b.step_period_s : 1.0 / world.scene().clock.haptic_rate_hz;
  std::unique_ptr<ModelInstance> instance =
      world.make_model(model, params, *b.topology, dt, {world.scene().path, 0, 0, "bodies." + b.name + ".model"});
  // Free what the haptic thread retired, then post; an unconsumed earlier request is replaced.
  for (ModelInstance* m = b.mailbox->retired.exchange(nullptr, std::memory_order_acquire); m != nullptr;) {
    ModelInstance* next = m->retired_next;
    delete m;
    m = next;
  }
  delete b.mailbox->incoming.exchange(instance.release(), std::memory_order_acq_rel);
  impl_->requested_models[body] = model;
}

bool Simulation::device_input(size_t device, const double* values, uint32_t count) {
  World& world = impl_->world;
  if (device >= world.device_count())
    throw InputError({world.scene().path, 0, 0, "devices"}, "no device with index " + std::to_string(device));
  return world.device(device).device->input(values, count);
}

size_t Simulation::device_count() const { return impl_->world.device_count(); }
const std::string& Simulation::device_plugin(size_t device) const { return impl_->world.device(device).desc.plugin; }

void Simulation::request_stop() noexcept { impl_->stop.store(true, std::memory_order_relaxed); }
size_t Simulation::body_count() const { return impl_->world.body_count(); }
std::vector<std::string> Simulation::load_warnings() const {
  std::vector<std::string> warnings;
  for (size_t i = 0; i < impl_->world.body_count(); ++i)
    if (!impl_->world.body(i).load_warning.empty()) warnings.push_back(impl_->world.body(i).load_warning);
  return warnings;
}
const std::string& Simulation::body_name(size_t body) const { return impl_->world.body(body).name; }
const std::string& Simulation::body_model(size_t body) const { return impl_->requested_models.at(body); }

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
  // The scene's own duration was checked at load; one given here (tacta compare --duration,
  // tacta snapshot --at, the viewer) is checked now, before the record buffers are sized from it.
  const SourceLocation run_duration{scene.path, 0, 0, "the run's duration (overriding clock.duration_s)"};
  if (!std::isfinite(schedule.duration_s) || schedule.duration_s < 0)
    throw InputError(run_duration, "expected a duration in s >= 0, found " + std::to_string(schedule.duration_s));
  if (const std::string problem = duration_limit_problem(schedule.duration_s, schedule.haptic_rate_hz, scene.devices.size());
      !problem.empty())
    throw InputError(run_duration, problem);
  schedule.realtime.priority = scene.clock.haptic_priority;
  schedule.realtime.cpu = scene.clock.haptic_cpu;
  schedule.realtime.lock_memory = scene.clock.lock_memory;
  schedule.realtime.spin_us = scene.clock.spin_us;
  if (options.progress) schedule.on_progress = print_progress;
  schedule.stop = &impl_->stop;

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
  HapticLoop loop(world, snapshots, expected_ticks, schedule.duration_s);
  if (!options.record_log.empty()) {
    if (world.device_count() == 0) throw InputError({scene.path, 0, 0, "devices"}, "--record: the scene has no device to record");
    loop.enable_device_log(expected_ticks);
  }
  if (impl_->haptics) loop.add_interaction(impl_->haptics.get());
  if (impl_->response) loop.add_interaction(impl_->response.get());
  const SceneStatic scene_static = describe(world);
  std::vector<FrameObserver*> observers = options.observers;
  std::unique_ptr<FrameObserver> vtk;
  if (scene.output.vtk && !options.out_dir.empty()) {
    vtk = make_vtk_observer(options.out_dir + "/vtk", scene.output.vtk_interval_s);
    observers.push_back(vtk.get());
  }
  std::unique_ptr<FrameObserver> surface_feed = make_device_surface_feed(world);
  if (surface_feed) observers.push_back(surface_feed.get());
  for (FrameObserver* o : observers) o->on_start(scene_static);
  OutputRenderTask render(snapshots, scene_static, observers);
  loop.start_workers(schedule.mode == ClockMode::Lockstep, expected_ticks);
  result.schedule = run_schedule(loop, render, schedule);
  loop.stop_workers();
  impl_->stop.store(false, std::memory_order_relaxed);  // a stop ends one run; a later run() runs again
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
    br.mesh = describe_body_mesh(b.topology->mesh, b.topology->load);
    br.mesh_warnings = b.topology->load.warnings;
    br.max_displacement_m = b.max_displacement_m;
    br.kinetic_energy_J = b.kinetic_energy();
    br.elastic_energy_J = b.model->elastic_energy(b.positions.data());
    br.model_counters = b.model->counters();
    br.frozen = b.fault.frozen;
    br.own_thread = b.own_thread;
    br.step_rate_hz = b.step_period_s > 0 ? 1.0 / b.step_period_s : 0.0;
    if (const BodyWorker* w = loop.worker(i)) {
      br.worker_steps = w->stats().steps;
      br.worker_step_ms = w->step_ms().summary();
      br.late_boundaries = w->stats().late_boundaries;
      br.max_lateness_s = w->stats().max_lateness_s;
    }
    if (b.fault.frozen) br.fault = b.fault.reason.data();
    arrays.push_back(&b.positions);
  }
  result.state_hash = hash_positions(arrays);
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceSlot& slot = world.device(d);
    result.devices.push_back({slot.name, slot.desc.plugin, slot.state, slot.stats.max_force_N,
                              slot.stats.contact_ticks, slot.stats.reconnections, slot.device->counters()});
  }
  result.faults = loop.faults().rows().size();
  for (const FaultRecord& f : loop.faults().rows()) {
    const std::string who = f.body >= 0   ? "body " + world.body(static_cast<size_t>(f.body)).name
                            : f.device >= 0 ? "device " + world.device(static_cast<size_t>(f.device)).name
                                            : std::string("run");
    char time[32];
    std::snprintf(time, sizeof time, "%.3f", f.time_s);
    result.fault_messages.push_back(who + " at t = " + time + " s: " + f.reason.data());
  }
  result.exit_code = result.faults > 0 ? 1 : 0;

  for (FrameObserver* o : observers)
    for (std::string& file : o->finish()) result.outputs.push_back(std::move(file));
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
