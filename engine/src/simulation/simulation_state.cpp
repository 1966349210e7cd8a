// The stepping half of Simulation: step, advance_to, state and loads between steps, parameter
// changes, and the report so far (see simulation.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "report/run_outputs.hpp"
#include "report/run_status_gather.hpp"
#include "simulation/simulation_impl.hpp"
#include "tacta/live_params.hpp"
#include "tacta/log.hpp"

namespace tacta {

namespace {

size_t element_count(const VolumeMesh& m) {
  return m.tets.size() / 4 + m.quads.size() / 4 +
         (m.dimension == 2 && m.quads.empty() ? m.triangles.size() / 3 : 0);
}

}  // namespace

void write_outputs_into(const std::string& dir, const HapticLoop& loop, const World& world,
                        RunResult& result) {
  std::filesystem::create_directories(dir);
  write_csv_records(dir, loop, world, result);
  std::vector<std::string> warnings;
  write_plots(dir, world, result, warnings);
  for (const std::string& w : warnings) log_warning(w);
  write_report_json(dir, loop, world, result);
}

RunResult Simulation::Impl::collect(const ScheduleResult& schedule) const {
  const ClockSession& session = *clock;
  const HapticLoop& loop = session.loop();
  RunResult result;
  result.scene = world.scene().path;
  result.mode = "lockstep";
  result.schedule = schedule;
  result.sim_time_s = session.time();
  std::vector<const std::vector<double>*> arrays;
  for (size_t i = 0; i < world.body_count(); ++i) {
    const SoftBody b = world.body(i);
    BodyResult br;
    br.initial_energy_J = b.presence.added_s >= 0 || i >= session.initial_energy_J.size()
                              ? b.presence.initial_energy_J
                              : session.initial_energy_J[i];
    br.added_s = b.presence.added_s;
    br.removed_s = b.presence.removed_s;
    br.pending = b.presence.state == BodyPresence::kPending;
    br.name = b.info.name;
    br.model = b.model.instance->name();
    br.nodes = b.node_count();
    br.fixed_nodes = static_cast<size_t>(
        std::count(b.shape.topology->fixed.begin(), b.shape.topology->fixed.end(), 1));
    br.elements = element_count(b.shape.topology->mesh);
    br.mesh = describe_body_mesh(b.shape.topology->mesh, b.shape.topology->load);
    br.mesh_warnings = b.shape.topology->load.warnings;
    br.max_displacement_m = b.fault.max_displacement_m;
    br.kinetic_energy_J = b.kinetic_energy();
    br.elastic_energy_J = b.model.instance->elastic_energy(b.nodes.positions.data());
    br.model_counters = b.model.instance->counters();
    br.frozen = b.fault.frozen;
    br.own_thread = b.settings.own_thread;
    br.step_rate_hz = b.settings.period_s > 0 ? 1.0 / b.settings.period_s : 0.0;
    if (const BodyWorker* w = loop.worker(i)) {
      br.worker_steps = w->stats().steps;
      br.worker_step_ms = w->step_ms().summary();
      br.late_boundaries = w->stats().late_boundaries;
      br.max_lateness_s = w->stats().max_lateness_s;
    }
    if (b.fault.frozen) br.fault = b.fault.reason.data();
    result.bodies.push_back(std::move(br));
    arrays.push_back(&b.nodes.positions);
  }
  result.state_hash = hash_positions(arrays);
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceComponents dev = world.device(d);
    result.devices.push_back({dev.link.name, dev.link.desc.plugin, dev.link.state,
                              dev.stats.max_force_N, dev.stats.contact_ticks,
                              dev.stats.reconnections, dev.link.device->counters(),
                              world.tool(d).revision});
  }
  result.faults = loop.faults().rows().size();
  for (const FaultRecord& f : loop.faults().rows()) {
    const std::string who =
        f.body >= 0     ? "body " + world.body(static_cast<size_t>(f.body)).info.name
        : f.device >= 0 ? "device " + world.device(static_cast<size_t>(f.device)).link.name
                        : std::string("run");
    char time[32];
    std::snprintf(time, sizeof time, "%.3f", f.time_s);
    result.fault_messages.push_back(who + " at t = " + time + " s: " + f.reason.data());
  }
  result.status = collect_run_status(loop, world, collision.get());
  result.exit_code = result.faults > 0 || result.status.errors > 0 ? 1 : 0;
  return result;
}

StepResult Simulation::step(uint64_t ticks) {
  ClockSession& session = impl_->session();
  const uint64_t ran = session.step(ticks, &impl_->stop);
  return {ran, session.step_status()};
}

StepResult Simulation::advance_to(double time_s) {
  ClockSession& session = impl_->session();
  if (!std::isfinite(time_s))
    throw InputError({scene().path, 0, 0, "advance_to"}, "expected a finite time in s");
  const double ticks = std::floor((time_s - session.time()) / session.dt() + 0.5);
  if (!(ticks > 0)) return {};  // the clock never goes back
  return step(static_cast<uint64_t>(ticks));
}

double Simulation::time() const noexcept { return impl_->clock ? impl_->clock->time() : 0.0; }
uint64_t Simulation::tick() const noexcept { return impl_->clock ? impl_->clock->tick() : 0; }
double Simulation::dt() const noexcept { return 1.0 / impl_->world.scene().clock.haptic_rate_hz; }
Snapshot Simulation::snapshot() {
  ClockSession& session = impl_->session();
  Snapshot s = HapticLoop::make_prototype(impl_->world);
  session.loop().capture(s, session.time());
  return s;
}
const SceneStatic& Simulation::scene_static() { return impl_->session().scene_static(); }
void Simulation::attach(FrameObserver* observer) { impl_->session().attach(observer); }
void Simulation::detach(FrameObserver* observer) {
  if (impl_->clock) impl_->clock->detach(observer);
}

BodyArrays Simulation::body_arrays(BodyHandle handle) {
  const SoftBody b = impl_->world.body(impl_->body_at(handle));
  return {b.node_count(),  b.nodes.positions.data(),       b.nodes.velocities.data(),
          b.rest().data(), b.shape.topology->fixed.data(), b.shape.topology->masses.data()};
}

void Simulation::state_written(BodyHandle handle) {
  const SoftBody b = impl_->world.body(impl_->body_at(handle));
  // The model's history (previous positions, warm starts) no longer matches the state.
  const tacta_body_state state = b.state_view(time());
  b.model.instance->begin(state, b.step_dt(dt()));
}

const VolumeMesh& Simulation::body_mesh(BodyHandle handle) const {
  return impl_->world.body(impl_->body_at(handle)).shape.topology->mesh;
}

const std::vector<uint32_t>& Simulation::surface_triangles(BodyHandle handle) const {
  const SoftBody b = impl_->world.body(impl_->body_at(handle));
  return b.surface.mesh ? b.surface.mesh->triangles : b.shape.topology->mesh.triangles;
}

std::vector<double> Simulation::surface_positions(BodyHandle handle) const {
  const SoftBody b = impl_->world.body(impl_->body_at(handle));
  if (!b.surface.mesh) return b.nodes.positions;
  // From the nodes: the surface's own positions are current only where the proxy last looked.
  std::vector<double> positions(b.surface.mesh->positions.size());
  interpolate_to_surface(*b.surface.mesh, b.nodes.positions.data(), positions.data());
  return positions;
}

void Simulation::set_applied_forces(BodyHandle handle, const std::vector<uint32_t>& nodes,
                                    const std::vector<double>& forces) {
  const SoftBody b = impl_->world.body(impl_->body_at(handle));
  const SourceLocation where{scene().path, 0, 0, "bodies." + b.info.name + " applied forces"};
  if (forces.size() != 3 * nodes.size())
    throw InputError(where, "expected 3 force components (N) per node, found " +
                                std::to_string(forces.size()) + " for " +
                                std::to_string(nodes.size()) + " nodes");
  std::vector<double> applied(3 * b.node_count(), 0.0);
  for (size_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i] >= b.node_count())
      throw InputError(where, "node " + std::to_string(nodes[i]) + " is past the body's " +
                                  std::to_string(b.node_count()) + " nodes");
    for (size_t k = 0; k < 3; ++k) {
      if (!std::isfinite(forces[3 * i + k])) throw InputError(where, "expected finite forces (N)");
      applied[3 * nodes[i] + k] += forces[3 * i + k];
    }
  }
  b.loads.applied_forces = std::move(applied);
}

void Simulation::clear_applied_forces(BodyHandle handle) {
  impl_->world.body(impl_->body_at(handle)).loads.applied_forces.clear();
}

double Simulation::kinetic_energy(BodyHandle handle) const {
  return impl_->world.body(impl_->body_at(handle)).kinetic_energy();
}

double Simulation::elastic_energy(BodyHandle handle) const {
  const SoftBody b = impl_->world.body(impl_->body_at(handle));
  return b.model.instance->elastic_energy(b.nodes.positions.data());
}

bool Simulation::set_param(BodyHandle handle, const std::string& name, double value) {
  const size_t body = impl_->body_at(handle);
  const SoftBody b = impl_->world.body(body);
  // The model running now, or the one a pending swap brings in.
  const bool pending = b.model.mailbox->incoming.load() != nullptr;
  const std::string model =
      pending ? impl_->requested_models[body] : std::string(b.model.instance->name());
  // A scheduled swap (bodies.*.swaps) may have changed the model: its parameters start from defaults.
  const ParamSet asked =
      model == impl_->requested_models[body] ? impl_->requested_params[body] : ParamSet{};
  const SourceLocation where{scene().path, 0, 0, "bodies." + b.info.name + ".params." + name};
  const LoadedDescriptor* found = impl_->plugins.find(TACTA_KIND_MODEL, model);
  if (found == nullptr) throw InputError(where, "no model plugin '" + model + "'");
  const tacta_descriptor& d = *found->descriptor;
  const uint32_t index = param_index(d, name);
  if (index == d.param_count)
    throw InputError(where, "model '" + std::string(d.name) + "' has no parameter '" + name + "'");
  const tacta_param_spec& spec = d.params[index];
  if (spec.type == TACTA_PARAM_TEXT || spec.type == TACTA_PARAM_CHOICE ||
      spec.type == TACTA_PARAM_VECTOR)
    throw InputError(where, "set_param takes numbers (REAL, INT, BOOL); change '" + name +
                                "' with a model swap");
  if (!std::isfinite(value) || value < spec.min_value || value > spec.max_value ||
      (spec.type != TACTA_PARAM_REAL && value != std::floor(value)))
    throw InputError(
        where,
        "expected " + std::string(spec.type == TACTA_PARAM_REAL ? "a number" : "an integer") +
            " in [" + std::to_string(spec.min_value) + ", " + std::to_string(spec.max_value) +
            "] " + spec.unit + ", found " + std::to_string(value));
  ParamSet params = complete_params(d, asked);
  params.set_number(name, value);
  // A live parameter (the schema's live list) changes in place while nothing steps the model and no
  // swap waits: between steps, on a haptic-thread body. Any other change is a swap.
  const bool quiet = !impl_->running.load() && !b.settings.own_thread && !pending;
  std::string why;
  if (quiet && is_live_param(d, name) &&
      b.model.instance->set_param(index, tacta_param_value{value, nullptr, nullptr, 0}, why)) {
    impl_->requested_params[body] = std::move(params);
    return true;
  }
  request_model_swap(handle, model, params);
  return false;
}

DeviceReading Simulation::device_reading(DeviceHandle device) const {
  const DeviceComponents dev = impl_->world.device(impl_->device_at(device));
  DeviceReading r;
  for (size_t k = 0; k < 3; ++k) {
    r.position[k] = dev.link.sample.position[k];
    r.proxy[k] = dev.contact.proxy[k];
    r.force[k] = dev.contact.force[k];
  }
  r.state = dev.link.state;
  r.in_contact = dev.contact.in_contact;
  return r;
}

RunResult Simulation::report() const {
  if (!impl_->clock) impl_->session();
  return impl_->collect(impl_->clock->totals());
}

std::vector<std::string> Simulation::write_outputs(const std::string& dir) {
  RunResult result = report();
  write_outputs_into(dir, impl_->clock->loop(), impl_->world, result);
  return result.outputs;
}

std::string Simulation::write_report(const std::string& dir) {
  RunResult result = report();
  std::filesystem::create_directories(dir);
  write_report_json(dir, impl_->clock->loop(), impl_->world, result);
  return dir + "/report.json";
}

const SceneDesc& Simulation::scene() const { return impl_->world.scene(); }

}  // namespace tacta
