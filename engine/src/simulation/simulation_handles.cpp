// Simulation's handles and lookups: bodies and devices by name, the live lists, and the check
// every handle passes before it reaches an index (see tacta/sim/handle.hpp).
#include <atomic>

#include "scene/did_you_mean.hpp"
#include "simulation/simulation_impl.hpp"

namespace tacta {

namespace {

// "unknown body 'x'; did you mean 'y'? (expected one of: ...)", or that the scene has none.
std::string unknown(const std::string& noun, const std::string& name,
                    const std::vector<std::string>& names) {
  if (names.empty()) return "unknown " + noun + " '" + name + "': the scene has no " + noun;
  return scene_detail::unknown_name_message(noun, name, names);
}

}  // namespace

uint32_t Simulation::Impl::next_salt() noexcept {
  // Distinct per Simulation in a process; the golden-ratio step spreads consecutive ones apart.
  static std::atomic<uint32_t> count{0};
  return (count.fetch_add(1, std::memory_order_relaxed) + 1) * 0x9e3779b9u;
}

size_t Simulation::Impl::body_at(BodyHandle body) const {
  const SourceLocation where{world.scene().path, 0, 0, "bodies"};
  if (body.index >= world.body_count())
    throw InputError(where, "no body handle " + to_string(body) + " in this simulation (" +
                                std::to_string(world.body_count()) +
                                " body slots in use; a default handle names none)");
  if (world.is_live(entity_of(body))) return body.index;
  const std::string& name = world.body(body.index).info.name;
  if (world.is_live(world.body_handle(body.index)))
    throw InputError(where, "body handle " + to_string(body) +
                                " is from another simulation (here #" + std::to_string(body.index) +
                                " is body '" + name + "')");
  throw InputError(where,
                   "stale body handle " + to_string(body) + ": body '" + name + "' was removed");
}

size_t Simulation::Impl::device_at(DeviceHandle device) const {
  const SourceLocation where{world.scene().path, 0, 0, "devices"};
  if (device.index >= world.device_count())
    throw InputError(where, "no device handle " + to_string(device) + " in this simulation (" +
                                std::to_string(world.device_count()) + " devices)");
  if (device.generation != salt)
    throw InputError(where, "device handle " + to_string(device) +
                                " is from another simulation (here #" +
                                std::to_string(device.index) + " is device '" +
                                world.device(device.index).link.name + "')");
  return device.index;
}

BodyHandle Simulation::body(const std::string& name) const {
  const World& world = impl_->world;
  std::vector<std::string> names;
  for (size_t i = 0; i < world.body_count(); ++i) {
    const BodyHandle h = impl_->body_handle(i);
    if (world.body(i).info.name != name) {
      if (body_alive(h)) names.push_back(world.body(i).info.name);
      continue;
    }
    if (!body_alive(h))
      throw InputError({world.scene().path, 0, 0, "bodies." + name},
                       "body '" + name + "' was removed");
    return h;
  }
  throw InputError({world.scene().path, 0, 0, "bodies"}, unknown("body", name, names));
}

std::vector<BodyHandle> Simulation::bodies() const {
  std::vector<BodyHandle> out;
  for (size_t i = 0; i < impl_->world.body_count(); ++i)
    if (const BodyHandle h = impl_->body_handle(i); body_alive(h)) out.push_back(h);
  return out;
}

bool Simulation::body_alive(BodyHandle body) const noexcept {
  return impl_->world.is_live(impl_->entity_of(body));
}

DeviceHandle Simulation::device(const std::string& name) const {
  const World& world = impl_->world;
  std::vector<std::string> names;
  for (size_t d = 0; d < world.device_count(); ++d) {
    if (world.device(d).link.name == name) return impl_->device_handle(d);
    names.push_back(world.device(d).link.name);
  }
  throw InputError({world.scene().path, 0, 0, "devices"}, unknown("device", name, names));
}

std::vector<DeviceHandle> Simulation::devices() const {
  std::vector<DeviceHandle> out;
  for (size_t d = 0; d < impl_->world.device_count(); ++d) out.push_back(impl_->device_handle(d));
  return out;
}

const std::string& Simulation::body_name(BodyHandle body) const {
  return impl_->world.body(impl_->body_at(body)).info.name;
}
const std::string& Simulation::body_model(BodyHandle body) const {
  return impl_->requested_models.at(impl_->body_at(body));
}
const ParamSet& Simulation::body_params(BodyHandle body) const {
  return impl_->requested_params.at(impl_->body_at(body));
}
const std::string& Simulation::device_name(DeviceHandle device) const {
  return impl_->world.device(impl_->device_at(device)).link.name;
}
const std::string& Simulation::device_plugin(DeviceHandle device) const {
  return impl_->world.device(impl_->device_at(device)).link.desc.plugin;
}

}  // namespace tacta
