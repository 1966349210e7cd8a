#include "world/world.hpp"

#include <algorithm>

#include "plugin/complete_params.hpp"

namespace tacta {

namespace {
constexpr double kSetupDt = 1e-3;  // s; only used for a default when a model is created alone

template <class... Ts>
void reserve_each(ecs::Registry& registry, size_t slots) {
  (registry.reserve<Ts>(slots), ...);
}
}  // namespace

World::World(const SceneDesc& scene, const PluginRegistry& plugins)
    : scene_(scene), plugins_(plugins), jobs_(std::make_unique<JobPool>(scene.threads)) {
  size_t event_bodies = 0;
  for (const BodyEventDesc& e : scene_.events) event_bodies += e.add ? 1 : 0;
  const size_t needed = scene_.bodies.size() + event_bodies;
  const size_t capacity =
      scene_.body_capacity > 0 ? scene_.body_capacity : needed + kSpareBodySlots;
  if (capacity < needed)
    throw InputError({scene_.path, 0, 0, "capacity.bodies"},
                     "capacity.bodies is " + std::to_string(capacity) +
                         " but the scene's bodies and events need " + std::to_string(needed) +
                         " slots");
  // Every slot's entity and storage are made now, so taking a body in or out at a tick boundary
  // allocates nothing. Entity index = body slot (bodies first, then their surfaces, devices,
  // tools and obstacles).
  descs_.reserve(capacity);
  generations_ = std::make_unique<std::atomic<uint32_t>[]>(capacity);
  reserve_body_components(capacity);
  const size_t entities = 2 * capacity + 2 * scene_.devices.size() + scene_.obstacles.size();
  reserve_each<DeviceLink, DeviceContact, DeviceStats, Tool, Collider>(registry_, entities);
  for (size_t i = 0; i < capacity; ++i) {
    const ecs::Entity e = registry_.create();
    emplace_body_components(e);
    body_entities_.push_back(e);
    generations_[i].store(e.generation, std::memory_order_relaxed);
  }
  // Then each slot's embedded surface entity (after the bodies: entity index = body slot).
  for (size_t i = 0; i < capacity; ++i) {
    const ecs::Entity surface = registry_.create();
    registry_.emplace<BodySurface>(surface, nullptr, static_cast<uint32_t>(i));
    registry_.emplace<SurfaceLink>(body_entities_[i], surface);
  }
  // An add and a remove per slot at most, and one tool change per device.
  commands_.resize(2 * capacity + scene_.devices.size());
  for (const BodyDesc& desc : scene_.bodies) {
    install(descs_.size(), build_body(desc));
    registry_.emplace<InScene>(body_entities_[descs_.size()]);
    descs_.push_back(desc);
  }
  // The scene's timed events: their bodies are built now and wait, pending, for their time.
  std::vector<std::string> names;
  for (const BodyDesc& b : scene_.bodies) names.push_back(b.name);
  for (const BodyEventDesc& e : scene_.events) {
    if (e.cut) continue;  // cuts are Simulation's (simulation_cut.cpp), between lockstep ticks
    EntityCommand c{e.add ? EntityCommand::kAddBody : EntityCommand::kRemoveBody, 0, e.time};
    if (e.change_tool) {  // built with the devices, below
      timed_.push_back({EntityCommand::kChangeTool, 0, e.time,
                        static_cast<uint32_t>(&e - scene_.events.data())});
      continue;
    }
    if (e.add) {
      if (std::find(names.begin(), names.end(), e.add->name) != names.end())
        throw InputError(e.where, "duplicate body name '" + e.add->name +
                                      "' (body names are unique, removed ones too)");
      BodyParts parts = build_body(*e.add);
      parts.presence.state = BodyPresence::kPending;
      install(descs_.size(), std::move(parts));
      c.slot = static_cast<uint32_t>(descs_.size());
      descs_.push_back(*e.add);
      names.push_back(e.add->name);
    } else {
      const auto it = std::find(names.begin(), names.end(), e.remove);
      if (it == names.end())
        throw InputError(e.where, "no body named '" + e.remove +
                                      "' before this event (bodies and earlier adds)");
      c.slot = static_cast<uint32_t>(it - names.begin());
    }
    timed_.push_back(c);
  }
  body_count_.store(descs_.size(), std::memory_order_release);
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
    DeviceLink link;
    link.name = desc.name;
    link.index = static_cast<uint32_t>(devices_.size());
    link.desc = desc;
    link.device = std::make_unique<DeviceInstance>(*found->descriptor, setup, desc.where);
    link.device->connect(desc.where);
    DeviceContact contact;
    contact.touched_body = desc.touches.empty() ? -1 : body_index(desc.touches);
    // Collision ids follow every body slot: the tools, then the obstacles.
    const auto tool_id = static_cast<uint32_t>(capacity + devices_.size());
    link.tool = registry_.create();
    registry_.emplace<Tool>(link.tool, build_tool(desc.tool, tool_id, link.index));
    const ecs::Entity e = registry_.create();
    registry_.emplace<DeviceLink>(e, std::move(link));
    registry_.emplace<DeviceContact>(e, contact);
    registry_.emplace<DeviceStats>(e);
    devices_.push_back(e);
  }
  pending_tools_ = std::make_unique<PendingTool[]>(scene_.devices.size());
  for (EntityCommand& c : timed_)  // the scene's tool changes, now that the devices exist
    if (c.kind == EntityCommand::kChangeTool) {
      const BodyEventDesc& e = scene_.events[c.item];
      const int device = device_index(e.change_tool->device);
      if (device < 0) throw InputError(e.where, "no device named '" + e.change_tool->device + "'");
      c.slot = static_cast<uint32_t>(device);
      c.item = static_cast<uint32_t>(timed_tools_.size());
      timed_tools_.push_back(build_tool(e.change_tool->tool, 0, c.slot));
    }
  for (const ObstacleDesc& obstacle : scene_.obstacles) {
    const auto id = static_cast<uint32_t>(capacity + scene_.devices.size() + colliders_.size());
    colliders_.push_back(registry_.create());
    registry_.emplace<Collider>(colliders_.back(), build_rigid_shape(obstacle.shape, id));
  }
}

DeviceComponents World::device(size_t i) const noexcept {
  const uint32_t e = devices_[i].index;
  return {registry_.pool<DeviceLink>().at(e), registry_.pool<DeviceContact>().at(e),
          registry_.pool<DeviceStats>().at(e)};
}

SoftBody World::body(size_t i) const noexcept {
  const uint32_t e = static_cast<uint32_t>(i);  // entity index = body slot
  return SoftBody{
      registry_.pool<BodyInfo>().at(e),
      registry_.pool<BodyPresence>().at(e),
      registry_.pool<NodeState>().at(e),
      registry_.pool<NodeLoads>().at(e),
      registry_.pool<RestShape>().at(e),
      registry_.pool<BodySurface>().at(registry_.pool<SurfaceLink>().at(e).surface.index),
      registry_.pool<BodyModel>().at(e),
      registry_.pool<BodySettings>().at(e),
      registry_.pool<StepProgress>().at(e),
      registry_.pool<BodyConstraints>().at(e),
      registry_.pool<FaultState>().at(e),
      registry_.pool<Recording>().at(e)};
}

void World::install(size_t slot, BodyParts&& p) noexcept {
  SoftBody b = body(slot);
  b.info = std::move(p.info);
  b.presence = p.presence;
  b.nodes = std::move(p.nodes);
  b.loads = std::move(p.loads);
  b.shape = std::move(p.shape);
  b.surface.mesh = std::move(p.surface.mesh);
  b.model = std::move(p.model);
  registry_.pool<BodySettings>().at(static_cast<uint32_t>(slot)) = p.settings;
  b.progress = p.progress;
  b.constraints = std::move(p.constraints);
  b.fault = p.fault;
  b.recording = std::move(p.recording);
}

BodyParts World::build_body(const BodyDesc& desc) const {
  const ModelFactory factory = [this](const std::string& model, const ParamSet& params,
                                      const BodyTopology& topology, double dt,
                                      const SourceLocation& where) {
    return make_model(model, params, topology, dt, where);
  };
  return build_soft_body(desc, scene_, factory);
}

int World::body_index(const std::string& name) const {
  for (size_t i = 0; i < body_count(); ++i)
    if (body(i).info.name == name) return static_cast<int>(i);
  return -1;
}

ecs::Entity World::add_body(const BodyDesc& desc, const std::function<void(size_t slot)>& prepare) {
  BodyParts built = build_body(desc);  // the heavy part, outside the lock
  if (built.settings.own_thread)
    throw InputError(
        desc.where,
        "a body added while the scene runs cannot have step_thread: own (its worker thread "
        "would start inside a tick); declare it under bodies or events");
  const std::lock_guard<std::mutex> lock(requests_);
  const size_t slot = body_count();
  if (body_index(desc.name) >= 0)
    throw InputError(desc.where, "a body named '" + desc.name +
                                     "' already exists (body names are unique, removed ones too)");
  if (slot >= body_capacity())
    throw InputError({scene_.path, 0, 0, "capacity.bodies"},
                     "no free body slot: capacity.bodies is " + std::to_string(body_capacity()) +
                         " (raise it in the scene to add more bodies while it runs)");
  built.presence.state = BodyPresence::kPending;
  install(slot, std::move(built));
  descs_.push_back(desc);  // reserved to capacity: never reallocates under a reader
  if (prepare) {
    try {
      prepare(slot);
    } catch (...) {
      descs_.pop_back();
      install(slot, BodyParts{});
      throw;
    }
  }
  body_count_.store(slot + 1, std::memory_order_release);
  commands_.push({EntityCommand::kAddBody, static_cast<uint32_t>(slot), 0});  // room for 2 per slot
  return body_entities_[slot];
}

void World::remove_body(ecs::Entity handle) {
  const std::lock_guard<std::mutex> lock(requests_);
  const size_t slot = body_slot(handle);
  generations_[slot].store(retired_generation(handle.generation), std::memory_order_release);
  commands_.push({EntityCommand::kRemoveBody, static_cast<uint32_t>(slot), 0});
}

int World::device_index(const std::string& name) const {
  for (size_t d = 0; d < devices_.size(); ++d)
    if (device(d).link.name == name) return static_cast<int>(d);
  return -1;
}

void World::change_tool(size_t d, const ShapeDesc& shape) {
  if (d >= device_count())
    throw InputError(
        {scene_.path, 0, 0, "devices"},
        "no device with index " + std::to_string(d) + " (" + std::to_string(device_count()) + ")");
  Tool built = build_tool(shape, 0, static_cast<uint32_t>(d));  // outside the lock
  const std::lock_guard<std::mutex> lock(requests_);
  PendingTool& p = pending_tools_[d];
  const std::string& name = device(d).link.name;
  if (p.waiting.load(std::memory_order_acquire))
    throw InputError({scene_.path, 0, 0, "devices." + name + ".tool"},
                     "a tool change for device '" + name +
                         "' is still waiting for the next tick (one at a time per device)");
  p.tool = std::move(built);  // frees the tool the last change took out, here
  p.waiting.store(true, std::memory_order_release);
  commands_.push({EntityCommand::kChangeTool, static_cast<uint32_t>(d), 0});
}

void World::swap_tool(size_t d, Tool& incoming) noexcept {
  Tool& current = tool(d);
  // The new shape takes over the old one's collision id and pose (the proxy moves it on).
  incoming.rigid.shape.body_id = current.rigid.shape.body_id;
  incoming.rigid.shape.pose_start = current.rigid.shape.pose_start;
  incoming.rigid.shape.pose_end = current.rigid.shape.pose_end;
  incoming.revision = current.revision + 1;
  std::swap(current, incoming);
}

ecs::Entity World::body_handle(size_t body) const {
  if (body >= body_count())
    throw InputError({scene_.path, 0, 0, "bodies"}, "no body with index " + std::to_string(body));
  return {body_entities_[body].index,
          generations_[body].load(std::memory_order_acquire) & ~kRemovedBit};
}

bool World::is_live(ecs::Entity handle) const noexcept {
  return handle.index < body_count() &&
         generations_[handle.index].load(std::memory_order_acquire) == handle.generation;
}

size_t World::body_slot(ecs::Entity handle) const {
  if (handle.index >= body_count())
    throw InputError({scene_.path, 0, 0, "bodies"},
                     "no body with handle " + ecs::to_string(handle) + " (" +
                         std::to_string(body_count()) + " body slots in use)");
  if (!is_live(handle))
    throw InputError({scene_.path, 0, 0, "bodies"},
                     "stale body handle " + ecs::to_string(handle) + ": body '" +
                         body(handle.index).info.name +
                         "' was removed (its handles' generation is now " +
                         std::to_string(generations_[handle.index].load(std::memory_order_acquire) &
                                        ~kRemovedBit) +
                         ")");
  return handle.index;
}

void World::apply_entity_commands(double time) noexcept {
  EntityCommand c;
  while (commands_.pop(c)) {
    if (c.kind == EntityCommand::kChangeTool) {
      PendingTool& p = pending_tools_[c.slot];
      swap_tool(c.slot, p.tool);
      p.waiting.store(false, std::memory_order_release);
    } else if (c.kind == EntityCommand::kAddBody) {
      enter(c.slot, time);
    } else {
      leave(c.slot, time);
    }
  }
  for (; next_timed_ < timed_.size() && timed_[next_timed_].time_s <= time + 1e-12; ++next_timed_) {
    const EntityCommand& t = timed_[next_timed_];
    if (t.kind == EntityCommand::kChangeTool) {
      swap_tool(t.slot, timed_tools_[t.item]);
      continue;
    }
    if (t.kind == EntityCommand::kAddBody) {
      enter(t.slot, time);
      continue;
    }
    // A timed removal retires the handle now, like a request would.
    const uint32_t g = generations_[t.slot].load(std::memory_order_relaxed);
    if ((g & kRemovedBit) == 0)
      generations_[t.slot].store(retired_generation(g), std::memory_order_release);
    leave(t.slot, time);
  }
}

void World::enter(size_t slot, double time) noexcept {
  const SoftBody b = body(slot);
  if (b.presence.state != BodyPresence::kPending) return;
  b.presence.state = BodyPresence::kPresent;
  b.presence.added_s = time;
  b.progress.next_step_s = time;
  b.presence.initial_energy_J = begin_model(b, time, 1.0 / scene_.clock.haptic_rate_hz);
  ecs::Pool<InScene>& in_scene = registry_.pool<InScene>();  // reserved for every slot
  if (!in_scene.contains(body_entities_[slot].index)) in_scene.emplace(body_entities_[slot]);
}

void World::leave(size_t slot, double time) noexcept {
  const SoftBody b = body(slot);
  if (b.presence.state == BodyPresence::kRemoved) return;
  b.presence.state = BodyPresence::kRemoved;
  b.presence.removed_s = time;
  // Out of every system; its components stay for the report (its handles are stale already).
  registry_.pool<InScene>().remove(body_entities_[slot].index);
}

// Every body component's pool, made now for every slot: filling, entering and leaving a slot
// later allocates nothing and never moves a component another thread holds.
void World::reserve_body_components(size_t slots) {
  reserve_each<InScene, BodyInfo, BodyPresence, NodeState, NodeLoads, RestShape, SurfaceLink,
               BodyModel, BodySettings, StepProgress, BodyConstraints, FaultState, Recording>(
      registry_, slots);
  registry_.reserve<BodySurface>(2 * slots);  // on the surface entities, after the bodies
}

void World::emplace_body_components(ecs::Entity e) {
  BodyPresence pending;
  pending.state = BodyPresence::kPending;
  registry_.emplace<BodyInfo>(e);
  registry_.emplace<BodyPresence>(e, pending);
  registry_.emplace<NodeState>(e);
  registry_.emplace<NodeLoads>(e);
  registry_.emplace<RestShape>(e);
  registry_.emplace<BodyModel>(e);
  registry_.emplace<BodySettings>(e);
  registry_.emplace<StepProgress>(e);
  registry_.emplace<BodyConstraints>(e);
  registry_.emplace<FaultState>(e);
  registry_.emplace<Recording>(e);
}

std::unique_ptr<ModelInstance> World::make_model(const std::string& model, const ParamSet& params,
                                                 const BodyTopology& topology, double dt,
                                                 const SourceLocation& where) const {
  const LoadedDescriptor* found = plugins_.find(TACTA_KIND_MODEL, model);
  if (found == nullptr)
    throw InputError(where, plugins_.unknown_name_message(TACTA_KIND_MODEL, model));
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
  auto instance = std::make_unique<ModelInstance>(*found->descriptor, setup, where, jobs_.get());
  instance->set_params(values);
  return instance;
}

}  // namespace tacta
