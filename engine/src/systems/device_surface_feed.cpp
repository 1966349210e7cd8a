#include "systems/device_surface_feed.hpp"

namespace tacta {

namespace {

class DeviceSurfaceFeed final : public FrameObserver {
 public:
  DeviceSurfaceFeed(World& world, std::vector<size_t> devices)
      : world_(world), devices_(std::move(devices)), shown_body_(devices_.size(), 0) {}

  void on_frame(const SceneStatic& scene, const Snapshot& snapshot) override {
    for (size_t k = 0; k < devices_.size(); ++k) {
      const size_t d = devices_[k];
      if (d >= snapshot.devices.size() || scene.bodies.empty()) continue;
      const int touched = snapshot.devices[d].touched_body;
      if (touched >= 0 && static_cast<size_t>(touched) < scene.bodies.size())
        shown_body_[k] = static_cast<size_t>(touched);
      const size_t b = shown_body_[k];
      const BodyStatic& body = scene.bodies[b];
      // The surface the body is drawn and touched through: its embedded one when it has one,
      // unless the scene asks for the simulation tets' boundary (stream_surface: simulation).
      const bool embedded =
          !world_.device(d).link.desc.stream_simulation_surface &&
          !body.surface_triangles.empty() &&
          snapshot.bodies[b].surface_positions.size() == body.surface_rest_positions.size();
      const std::vector<double>& positions =
          embedded ? snapshot.bodies[b].surface_positions : snapshot.bodies[b].positions;
      const std::vector<uint32_t>& triangles = embedded ? body.surface_triangles : body.triangles;
      const tacta_device_surface surface{
          snapshot.time_s,  body.name.c_str(),
          positions.data(), static_cast<uint32_t>(positions.size() / 3),
          triangles.data(), static_cast<uint32_t>(triangles.size() / 3)};
      world_.device(d).link.device->surface(surface);
    }
  }

 private:
  World& world_;
  std::vector<size_t> devices_;     // indices of the devices that take a surface
  std::vector<size_t> shown_body_;  // per such device: the body it is shown
};

}  // namespace

std::unique_ptr<FrameObserver> make_device_surface_feed(World& world) {
  std::vector<size_t> devices;
  for (size_t d = 0; d < world.device_count(); ++d)
    if (world.device(d).link.device->wants_surface()) devices.push_back(d);
  if (devices.empty()) return nullptr;
  return std::make_unique<DeviceSurfaceFeed>(world, std::move(devices));
}

}  // namespace tacta
