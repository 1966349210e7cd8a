#include "tacta/sim/simulation.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

#include "output/vtk_observer.hpp"
#include "report/run_outputs.hpp"
#include "simulation/simulation_impl.hpp"
#include "tacta/sim/registry_schemas.hpp"
#include "text/digest.hpp"

namespace tacta {

namespace {

void print_progress(double fraction) {
  const int width = 40;
  const int filled = static_cast<int>(fraction * width + 0.5);
  std::fprintf(stderr, "\r[%.*s%*s] %3d%%", filled, "########################################",
               width - filled, "", static_cast<int>(fraction * 100 + 0.5));
  std::fflush(stderr);
}

}  // namespace

std::string hash_positions(const std::vector<const std::vector<double>*>& arrays) {
  uint64_t h = fnv1a64(nullptr, 0);  // the offset basis
  for (const std::vector<double>* a : arrays) h = fnv1a64(a->data(), a->size() * sizeof(double), h);
  return hex64(h);
}

Simulation::Simulation(const SceneDesc& scene, const PluginRegistry& plugins)
    : impl_(std::make_unique<Impl>(scene, plugins)) {
  // Reserved for every slot: a body added from another thread never moves these under a reader.
  impl_->requested_models.reserve(impl_->world.body_capacity());
  impl_->requested_params.reserve(impl_->world.body_capacity());
  for (size_t i = 0; i < impl_->world.body_count(); ++i) {
    impl_->requested_models.push_back(impl_->world.body_desc(i).model);
    impl_->requested_params.push_back(impl_->world.body_desc(i).model_params);
  }
  // clock.resume: the Simulation opens where the checkpoint stands, for every front end.
  if (!scene.clock.resume.empty()) restore_state(scene.clock.resume);
}

BodyHandle Simulation::add_body(const BodyDesc& desc) {
  // Outside run() the calling thread is the one that runs the ticks (step, advance_to): the
  // body's collision surface and render entries are made here, before its command is posted,
  // and the tick only lets it in. During run() the tick runs on another thread: neither is made.
  const bool between_steps = !impl_->running.load();
  const ecs::Entity e = impl_->world.add_body(desc, [&](size_t slot) {
    if (!between_steps) return;
    if (impl_->collision) impl_->collision->add_surface(slot);
    if (impl_->clock) impl_->clock->add_body(slot);
  });
  impl_->requested_models.push_back(desc.model);
  impl_->requested_params.push_back(desc.model_params);
  return impl_->handle_of(e);
}

BodyHandle Simulation::add_body(const std::string& yaml) {
  return add_body(
      load_body_from_string(yaml, impl_->world.scene().path, RegistrySchemas(impl_->plugins)));
}

void Simulation::change_tool(DeviceHandle device, const ShapeDesc& tool) {
  impl_->world.change_tool(impl_->device_at(device), tool);
}

void Simulation::change_tool(DeviceHandle device, const std::string& yaml) {
  change_tool(device, load_shape_from_string(yaml, impl_->world.scene().path,
                                             RegistrySchemas(impl_->plugins)));
}

void Simulation::remove_body(BodyHandle body) {
  impl_->body_at(body);  // InputError naming a stale or foreign handle
  impl_->world.remove_body(impl_->entity_of(body));
}

void Simulation::request_model_swap(BodyHandle handle, const std::string& model,
                                    const ParamSet& params) {
  World& world = impl_->world;
  const size_t body = impl_->body_at(handle);
  const SoftBody b = world.body(body);
  const double dt = b.step_dt(1.0 / world.scene().clock.haptic_rate_hz);
  std::unique_ptr<ModelInstance> instance =
      world.make_model(model, params, *b.shape.topology, dt,
                       {world.scene().path, 0, 0, "bodies." + b.info.name + ".model"});
  // Free what the haptic thread retired, then post; an unconsumed earlier request is replaced.
  for (ModelInstance* m = b.model.mailbox->retired.exchange(nullptr, std::memory_order_acquire);
       m != nullptr;) {
    ModelInstance* next = m->retired_next;
    delete m;
    m = next;
  }
  delete b.model.mailbox->incoming.exchange(instance.release(), std::memory_order_acq_rel);
  impl_->requested_models[body] = model;
  impl_->requested_params[body] = params;
}

bool Simulation::device_input(DeviceHandle device, const double* values, uint32_t count) {
  return impl_->world.device(impl_->device_at(device)).link.device->input(values, count);
}

void Simulation::request_stop() noexcept { impl_->stop.store(true, std::memory_order_relaxed); }
std::vector<std::string> Simulation::load_warnings() const {
  std::vector<std::string> warnings;
  for (size_t i = 0; i < impl_->world.body_count(); ++i)
    if (!impl_->world.body(i).info.load_warning.empty())
      warnings.push_back(impl_->world.body(i).info.load_warning);
  return warnings;
}
Simulation::~Simulation() = default;

RunResult Simulation::run(const RunOptions& options) {
  World& world = impl_->world;
  const SceneDesc& scene = world.scene();
  ScheduleOptions schedule;
  schedule.mode =
      scene.clock.mode == ClockDesc::Mode::Realtime ? ClockMode::Realtime : ClockMode::Lockstep;
  if (options.realtime)
    schedule.mode = *options.realtime ? ClockMode::Realtime : ClockMode::Lockstep;
  schedule.haptic_rate_hz = scene.clock.haptic_rate_hz;
  schedule.render_rate_hz = scene.clock.render_rate_hz;
  schedule.duration_s = options.duration_s.value_or(scene.clock.duration_s);
  // The scene's own duration was checked at load; one given here (tacta compare --duration,
  // tacta snapshot --at, the viewer) is checked now, before the record buffers are sized from it.
  const SourceLocation run_duration{scene.path, 0, 0,
                                    "the run's duration (overriding clock.duration_s)"};
  if (!std::isfinite(schedule.duration_s) || schedule.duration_s < 0)
    throw InputError(run_duration,
                     "expected a duration in s >= 0, found " + std::to_string(schedule.duration_s));
  if (const std::string problem = duration_limit_problem(
          schedule.duration_s, schedule.haptic_rate_hz, scene.devices.size());
      !problem.empty())
    throw InputError(run_duration, problem);
  schedule.realtime.priority = scene.clock.haptic_priority;
  schedule.realtime.cpu = scene.clock.haptic_cpu;
  schedule.realtime.lock_memory = scene.clock.lock_memory;
  schedule.realtime.shallow_idle = scene.clock.shallow_idle;
  schedule.realtime.poll_idle = scene.clock.poll_idle;
  schedule.realtime.spin_us = scene.clock.spin_us;
  if (options.progress) schedule.on_progress = print_progress;
  schedule.stop = &impl_->stop;

  ClockSession& session = impl_->session();
  const auto expected_ticks =
      static_cast<size_t>(schedule.duration_s * schedule.haptic_rate_hz + 1);
  HapticLoop& loop = session.loop();
  if (!options.record_log.empty()) {
    if (world.device_count() == 0)
      throw InputError({scene.path, 0, 0, "devices"},
                       "--record: the scene has no device to record");
    loop.enable_device_log(expected_ticks);
  }
  // This run's observers (frames, VTK, a window) see its frames only.
  std::vector<FrameObserver*> observers = options.observers;
  std::unique_ptr<FrameObserver> vtk;
  if (scene.output.vtk && !options.out_dir.empty()) {
    vtk = make_vtk_observer(options.out_dir + "/vtk", scene.output.vtk_interval_s);
    observers.push_back(vtk.get());
  }
  for (FrameObserver* o : observers) session.attach(o);
  impl_->running.store(true);
  const ScheduleResult ran = session.run(schedule);
  impl_->running.store(false);
  for (FrameObserver* o : observers) session.detach(o);
  impl_->stop.store(false,
                    std::memory_order_relaxed);  // a stop ends one run; a later run() runs again
  if (options.progress) std::fprintf(stderr, "\n");
  RunResult result = impl_->collect(ran);
  result.mode = schedule.mode == ClockMode::Realtime ? "realtime" : "lockstep";

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
    write_outputs_into(options.out_dir, loop, world, result);
  }
  return result;
}

}  // namespace tacta
