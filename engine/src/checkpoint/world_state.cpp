#include "checkpoint/world_state.hpp"

#include <cstring>

#include "checkpoint/shape_state.hpp"

namespace tacta {

namespace {

enum : uint32_t { kBodySection = 0x424f4459, kDeviceSection = 0x44455643 };

void write_params(CheckpointWriter& out, const ParamSet& params) {
  out.pod(params.size());
  for (uint32_t i = 0; i < params.size(); ++i) {
    const tacta_param_value& v = params.data()[i];
    out.text(params.names()[i]);
    out.pod(v.number);
    out.pod(static_cast<uint8_t>(v.text != nullptr));
    out.text(v.text != nullptr ? v.text : "");
    out.array(v.values != nullptr ? std::vector<double>(v.values, v.values + v.count)
                                  : std::vector<double>{});
  }
}

ParamSet read_params(CheckpointReader& in) {
  const auto count = in.pod<uint32_t>("the parameter count");
  if (count > 4096) in.fail(std::to_string(count) + " parameters is past any model's");
  ParamSet params;
  for (uint32_t i = 0; i < count; ++i) {
    const std::string name = in.text("a parameter name");
    const auto number = in.pod<double>("a parameter value");
    const auto has_text = in.pod<uint8_t>("a parameter kind");
    const std::string text = in.text("a parameter text");
    std::vector<double> values = in.array<double>("a parameter vector", 1u << 20);
    if (has_text != 0)
      params.add_text(name, text, number);
    else if (!values.empty())
      params.add_vector(name, std::move(values));
    else
      params.add_number(name, number);
  }
  return params;
}

std::string params_bytes(const ParamSet& params) {
  CheckpointWriter w;
  write_params(w, params);
  return std::string(w.bytes().begin(), w.bytes().end());
}

}  // namespace

uint64_t scene_fingerprint(const World& world) {
  CheckpointWriter w;
  const SceneDesc& scene = world.scene();
  w.text(scene.name);
  w.pod(scene.clock.haptic_rate_hz);
  w.pod(scene.clock.render_rate_hz);
  w.pod(scene.seed);
  w.pod(scene.gravity);
  w.pod(static_cast<uint64_t>(scene.bodies.size()));
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const SoftBody b = world.body(i);
    w.text(b.info.name);
    // The mesh, material and held nodes the body was built from (--set on any of them counts),
    // before any cut.
    const BodyTopology& loaded = b.shape.loaded();
    w.pod(static_cast<uint64_t>(loaded.mesh.node_count()));
    w.pod(static_cast<uint64_t>(loaded.mesh.tets.size()));
    w.text(scene.bodies[i].model);
    write_params(w, scene.bodies[i].model_params);
    w.pod(b.settings.period_s);
    w.pod(loaded.material);
    w.array(loaded.mesh.positions);
    w.array(loaded.masses);
    w.array(loaded.fixed);
  }
  w.pod(static_cast<uint64_t>(world.device_count()));
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceLink& link = world.device(d).link;
    w.text(link.name);
    w.text(link.desc.plugin);
    write_params(w, link.desc.params);
    w.pod(link.desc.coupling_stiffness);
    w.pod(link.desc.coupling_damping);
    w.pod(link.desc.tool.radius);
  }
  return fnv1a64(w.bytes().data(), w.bytes().size());
}

void save_bodies(CheckpointWriter& out, World& world, const RequestedModels& requested) {
  out.pod(static_cast<uint64_t>(world.body_count()));
  for (size_t i = 0; i < world.body_count(); ++i) {
    const SoftBody b = world.body(i);
    const SourceLocation where{world.scene().path, 0, 0, "bodies." + b.info.name};
    std::string why;
    if (!b.model.instance->can_save_state(why))
      throw InputError(where, "cannot checkpoint body '" + b.info.name + "': " + why);
    if (b.settings.own_thread)
      throw InputError(where, "cannot checkpoint body '" + b.info.name +
                                  "': it steps on its own thread (step_thread: own)");
    if (b.model.mailbox->incoming.load() != nullptr)
      throw InputError(where, "cannot checkpoint body '" + b.info.name +
                                  "' while a model swap waits for the next tick: step once");
    const size_t at = out.begin_section(kBodySection);
    out.text(b.info.name);
    save_shape(out, b);
    out.pod(b.presence);
    out.array(b.nodes.positions);
    out.array(b.nodes.velocities);
    out.array(b.nodes.step_start);
    out.array(b.loads.external_forces);
    out.array(b.loads.contact_forces);
    out.array(b.loads.applied_forces);
    out.pod(static_cast<uint64_t>(b.model.next_swap));
    out.pod(static_cast<uint64_t>(b.model.runtime_swaps.size()));
    for (const RuntimeSwap& s : b.model.runtime_swaps) {
      out.pod(s.time_s);
      out.text(s.model);
    }
    out.pod(b.model.runtime_swaps_unlisted);
    out.text(b.model.instance->name());
    out.text(requested.models[i]);
    write_params(out, requested.params[i]);
    const std::vector<uint8_t> own = b.model.instance->save_state();
    out.blob(own);
    out.pod(b.progress);
    out.pod(b.fault);
    out.array(b.constraints.boundary ? b.constraints.boundary->save_state()
                                     : std::vector<double>{});
    out.end_section(at);
  }
}

std::vector<size_t> load_bodies(CheckpointReader& in, World& world, const PluginRegistry& plugins,
                                const RequestedModels& requested) {
  std::vector<size_t> reshaped;
  const auto count = in.pod<uint64_t>("the body count");
  if (count != world.body_count())
    in.fail(std::to_string(count) + " bodies in the checkpoint, " +
            std::to_string(world.body_count()) +
            " in the scene (bodies added while it ran are not restored)");
  const double haptic_dt = 1.0 / world.scene().clock.haptic_rate_hz;
  for (size_t i = 0; i < world.body_count(); ++i) {
    const SoftBody b = world.body(i);
    CheckpointReader r = in.section(kBodySection, "body '" + b.info.name + "'");
    const std::string name = r.text("the body name");
    if (name != b.info.name)
      r.fail("body " + std::to_string(i) + " is '" + name + "' in the checkpoint, '" + b.info.name +
             "' in the scene");
    const bool reshape = load_shape(r, world, i);
    if (reshape) reshaped.push_back(i);
    r.pod_into(b.presence, "presence");
    r.array_exact(b.nodes.positions, "node positions (3 per node)");
    r.array_exact(b.nodes.velocities, "node velocities (3 per node)");
    r.array_exact(b.nodes.step_start, "step start positions (3 per node)");
    r.array_exact(b.loads.external_forces, "external forces (3 per node)");
    r.array_exact(b.loads.contact_forces, "contact forces (3 per node)");
    if (reshape) shape_positions_loaded(b);
    b.loads.applied_forces = r.array<double>("applied forces", b.nodes.positions.size());
    if (!b.loads.applied_forces.empty() &&
        b.loads.applied_forces.size() != b.nodes.positions.size())
      r.fail("applied forces: " + std::to_string(b.loads.applied_forces.size()) +
             " numbers, expected none or 3 per node");
    // The scheduled swaps done by the checkpoint's time, as the tick does them (no begin()).
    const auto next_swap = r.pod<uint64_t>("the next scheduled swap");
    if (next_swap > b.model.swaps.size())
      r.fail(std::to_string(next_swap) + " scheduled swaps done, the scene has " +
             std::to_string(b.model.swaps.size()));
    for (; b.model.next_swap < next_swap; ++b.model.next_swap)
      std::swap(b.model.instance, b.model.swaps[b.model.next_swap].model);
    const auto swaps = r.pod<uint64_t>("the runtime swap count");
    if (swaps > b.model.runtime_swaps.capacity())
      r.fail(std::to_string(swaps) + " runtime swaps listed, room for " +
             std::to_string(b.model.runtime_swaps.capacity()));
    b.model.runtime_swaps.clear();
    for (uint64_t s = 0; s < swaps; ++s) {
      const auto time = r.pod<double>("a runtime swap time");
      const std::string model = r.text("a runtime swap model");
      const LoadedDescriptor* found = plugins.find(TACTA_KIND_MODEL, model);
      if (found == nullptr) r.fail("no model plugin '" + model + "' (a runtime swap)");
      b.model.runtime_swaps.push_back({time, found->descriptor->name});
    }
    r.pod_into(b.model.runtime_swaps_unlisted, "unlisted runtime swaps");
    const std::string running = r.text("the model running");
    requested.models[i] = r.text("the model asked for");
    requested.params[i] = read_params(r);
    const SourceLocation where{world.scene().path, 0, 0, "bodies." + b.info.name + ".model"};
    // A runtime swap or a parameter change: the instance is built afresh from what was asked.
    if (running == requested.models[i] &&
        (running != b.model.instance->name() ||
         params_bytes(requested.params[i]) != params_bytes(world.body_desc(i).model_params)))
      b.model.instance = world.make_model(running, requested.params[i], *b.shape.topology,
                                          b.settings.step_dt(haptic_dt), where);
    if (running != b.model.instance->name())
      r.fail("body '" + b.info.name + "' runs model '" + running + "' in the checkpoint, '" +
             b.model.instance->name() + "' here");
    const std::span<const uint8_t> own = r.blob("the model's own state");
    std::string why;
    if (!b.model.instance->load_state(own, why)) r.fail(why);
    r.pod_into(b.progress, "step progress");
    r.pod_into(b.fault, "fault state");
    const std::vector<double> boundary = r.array<double>("boundary motion state", 1u << 28);
    if (b.constraints.boundary ? !b.constraints.boundary->load_state(boundary) : !boundary.empty())
      r.fail("boundary motion state of " + std::to_string(boundary.size()) +
             " numbers does not match the scene's managed nodes");
    r.expect_end();
  }
  return reshaped;
}

std::vector<std::string> save_devices(CheckpointWriter& out, World& world) {
  std::vector<std::string> notes;
  out.pod(static_cast<uint64_t>(world.device_count()));
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceComponents dev = world.device(d);
    const size_t at = out.begin_section(kDeviceSection);
    out.text(dev.link.name);
    out.pod(dev.link.sample);
    out.pod(dev.link.state);
    out.pod(dev.link.status_reason);
    out.pod(dev.link.status_time_s);
    out.pod(dev.contact);
    out.pod(dev.stats);
    const BladeSweep& blade = world.tool(d).blade;  // a sweep in progress is cut after a restore
    out.pod(static_cast<uint8_t>(blade.enabled));
    out.pod(static_cast<uint8_t>(blade.held));
    out.pod(blade.last);
    out.array(blade.swept);
    out.pod(blade.first_s);
    out.pod(static_cast<uint8_t>(blade.released));
    out.pod(blade.dropped);
    out.pod(static_cast<uint8_t>(dev.link.device->has_state()));
    out.blob(dev.link.device->save_state());
    if (!dev.link.device->has_state())
      notes.push_back("device '" + dev.link.name + "' (" + dev.link.desc.plugin +
                      ") is a live link: its state is not saved; a restore reconnects it");
    out.end_section(at);
  }
  return notes;
}

std::vector<std::string> load_devices(CheckpointReader& in, World& world) {
  std::vector<std::string> notes;
  const auto count = in.pod<uint64_t>("the device count");
  if (count != world.device_count())
    in.fail(std::to_string(count) + " devices in the checkpoint, " +
            std::to_string(world.device_count()) + " in the scene");
  for (size_t d = 0; d < world.device_count(); ++d) {
    const DeviceComponents dev = world.device(d);
    CheckpointReader r = in.section(kDeviceSection, "device '" + dev.link.name + "'");
    const std::string name = r.text("the device name");
    if (name != dev.link.name)
      r.fail("device " + std::to_string(d) + " is '" + name + "' in the checkpoint, '" +
             dev.link.name + "' in the scene");
    r.pod_into(dev.link.sample, "the last sample");
    r.pod_into(dev.link.state, "the connection state");
    r.pod_into(dev.link.status_reason, "the status reason");
    dev.link.status_reason.back() = '\0';
    r.pod_into(dev.link.status_time_s, "the status time");
    r.pod_into(dev.contact, "the contact");
    r.pod_into(dev.stats, "the statistics");
    BladeSweep& blade = world.tool(d).blade;
    if ((r.pod<uint8_t>("whether the tool is a blade") != 0) != blade.enabled)
      r.fail("device '" + dev.link.name + "''s tool is a blade in one of the checkpoint and the " +
             "scene, not the other");
    blade.held = r.pod<uint8_t>("whether the blade's button was held") != 0;
    r.pod_into(blade.last, "the blade's last edge");
    const std::vector<double> swept =
        r.array<double>("the blade's sweep", 9 * BladeSweep::kCapacityTriangles);
    if (swept.size() % 9 != 0) r.fail("the blade's sweep is not 9 numbers a triangle");
    blade.swept.assign(swept.begin(), swept.end());  // within the capacity the tick relies on
    r.pod_into(blade.first_s, "when the blade's sweep began");
    blade.released = r.pod<uint8_t>("whether the blade's button was let go") != 0;
    r.pod_into(blade.dropped, "the blade's dropped triangles");
    const bool had_state = r.pod<uint8_t>("whether the plugin saved state") != 0;
    const std::span<const uint8_t> own = r.blob("the plugin's own state");
    std::string why;
    if (had_state && dev.link.device->has_state() && !dev.link.device->load_state(own, why))
      r.fail(why);
    if (!dev.link.device->has_state())
      notes.push_back("device '" + dev.link.name + "' (" + dev.link.desc.plugin +
                      ") is a live link: restored connected afresh, its own state not restored");
    r.expect_end();
  }
  return notes;
}

}  // namespace tacta
