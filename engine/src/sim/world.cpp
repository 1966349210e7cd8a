#include "world.hpp"

#include "param_defaults.hpp"

namespace tacta {

namespace {
constexpr double kSetupDt = 1e-3;  // s; only used for a default when a model is created alone
}

World::World(const SceneDesc& scene, const PluginRegistry& plugins)
    : scene_(scene), plugins_(plugins), jobs_(std::make_unique<JobPool>(scene.threads)) {
  const ModelFactory factory = [this](const std::string& model, const ParamSet& params,
                                      const BodyTopology& topology, double dt,
                                      const SourceLocation& where) {
    return make_model(model, params, topology, dt, where);
  };
  for (const BodyDesc& desc : scene_.bodies) {
    SoftBody body = build_soft_body(desc, scene_, factory);
    const ecs::Entity e = registry_.create();
    registry_.emplace<SoftBody>(e, std::move(body));
    bodies_.push_back(e);
  }
  for (const DeviceDesc& desc : scene_.devices) {
    const LoadedDescriptor* found = plugins_.find(TACTA_KIND_DEVICE, desc.plugin);
    if (found == nullptr)
      throw InputError(desc.where, plugins_.unknown_name_message(TACTA_KIND_DEVICE, desc.plugin));
    tacta_device_setup setup{};
    setup.struct_size = sizeof setup;
    setup.params = desc.params.data();
    setup.param_count = desc.params.size();
    setup.base_directory = scene_.directory.c_str();
    setup.seed = scene_.seed;
    setup.tick = 1.0 / scene_.clock.haptic_rate_hz;
    DeviceSlot slot;
    slot.name = desc.name;
    slot.desc = desc;
    slot.device = std::make_unique<DeviceInstance>(*found->descriptor, setup, desc.where);
    slot.device->connect(desc.where);
    slot.touched_body = desc.touches.empty() ? -1 : body_index(desc.touches);
    const ecs::Entity e = registry_.create();
    registry_.emplace<DeviceSlot>(e, std::move(slot));
    devices_.push_back(e);
  }
}

int World::body_index(const std::string& name) const {
  for (size_t i = 0; i < bodies_.size(); ++i)
    if (body(i).name == name) return static_cast<int>(i);
  return -1;
}

std::unique_ptr<ModelInstance> World::make_model(const std::string& model, const ParamSet& params,
                                                 const BodyTopology& topology, double dt,
                                                 const SourceLocation& where) const {
  const LoadedDescriptor* found = plugins_.find(TACTA_KIND_MODEL, model);
  if (found == nullptr) throw InputError(where, plugins_.unknown_name_message(TACTA_KIND_MODEL, model));
  const ParamSet values = complete_params(*found->descriptor, params);
  tacta_model_setup setup{};
  setup.struct_size = sizeof setup;
  setup.mesh = &topology.view;
  setup.material = &topology.material;
  setup.masses = topology.masses.data();
  setup.fixed = topology.fixed.data();
  setup.params = values.data();
  setup.param_count = values.size();
  setup.dt = dt > 0 ? dt : kSetupDt;
  return std::make_unique<ModelInstance>(*found->descriptor, setup, where, jobs_.get());
}

}  // namespace tacta
