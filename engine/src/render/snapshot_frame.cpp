#include "tacta/render/snapshot_frame.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "tacta/render/headless.hpp"
#include "tacta/render/image.hpp"

namespace tacta::render {

namespace {

// What a body shows: its embedded surface when it has one, else the boundary of its tets.
bool shows_embedded(const BodyStatic& b, const BodySnapshot& s) {
  return !b.surface_triangles.empty() &&
         s.surface_positions.size() == b.surface_rest_positions.size();
}

// Rest bounds of every body, for a camera that stays put while the bodies move.
void fit_to_rest(RenderFrame& frame, const SceneStatic& scene) {
  RenderFrame rest;
  for (const BodyStatic& b : scene.bodies) {
    BodyDraw d;
    const bool embedded = !b.surface_triangles.empty();
    d.positions = embedded ? b.surface_rest_positions : b.rest_positions;
    d.triangles = embedded ? b.surface_triangles : b.triangles;
    rest.bodies.push_back(std::move(d));
  }
  fit_camera(rest);
  frame.camera = rest.camera;
}

}  // namespace

RenderFrame make_render_frame(const SceneStatic& scene, const Snapshot& snapshot,
                              const SnapshotStyle& style) {
  RenderFrame frame;
  double max_displacement = 1e-4;  // m: the colour map's upper end at least 0.1 mm
  double floor = 1e300;
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodyStatic& b = scene.bodies[i];
    const BodySnapshot& s = snapshot.bodies[i];
    BodyDraw d;
    if (!s.present) {  // not in the scene yet, or removed: drawn as nothing, indices kept
      frame.bodies.push_back(std::move(d));
      continue;
    }
    const bool embedded = shows_embedded(b, s);
    const std::vector<double>& rest = embedded ? b.surface_rest_positions : b.rest_positions;
    d.positions = embedded ? s.surface_positions : s.positions;
    d.triangles = embedded ? b.surface_triangles : b.triangles;
    d.cut_triangles = embedded ? b.surface_cut_triangles : b.cut_triangles;
    d.wireframe = style.wireframe;
    if (style.colour_by_displacement) {
      d.scalar.resize(d.positions.size() / 3);
      for (size_t n = 0; n < d.scalar.size(); ++n) {
        const double dx = d.positions[3 * n] - rest[3 * n];
        const double dy = d.positions[3 * n + 1] - rest[3 * n + 1];
        const double dz = d.positions[3 * n + 2] - rest[3 * n + 2];
        d.scalar[n] = std::sqrt(dx * dx + dy * dy + dz * dz);
        max_displacement = std::max(max_displacement, d.scalar[n]);
      }
    }
    if (s.frozen) d.base_colour = {0.5f, 0.5f, 0.5f};
    for (uint32_t n : b.fixed_nodes)
      for (int a = 0; a < 3; ++a)
        d.fixed_positions.push_back(s.positions[3 * n + static_cast<size_t>(a)]);
    for (size_t k = 1; k < b.rest_positions.size(); k += 3)
      floor = std::min(floor, b.rest_positions[k]);
    frame.bodies.push_back(std::move(d));
  }
  for (BodyDraw& d : frame.bodies) d.scalar_max = max_displacement;
  frame.floor_height = floor < 1e300 ? floor : 0.0;
  fit_to_rest(frame, scene);

  char line[160];
  std::snprintf(line, sizeof line, "t = %.3f s   tick %.3f ms", snapshot.time_s,
                snapshot.last_tick_ms);
  frame.overlay_lines.emplace_back(line);
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    std::snprintf(line, sizeof line, "%s: %s%s  max |u| %.2f mm", scene.bodies[i].name.c_str(),
                  snapshot.bodies[i].model.c_str(), snapshot.bodies[i].frozen ? " (FROZEN)" : "",
                  1e3 * snapshot.bodies[i].max_displacement_m);
    frame.overlay_lines.emplace_back(line);
  }
  if (!style.model_label.empty()) frame.overlay_lines.push_back(style.model_label);
  if (!snapshot.devices.empty() && !scene.devices.empty()) {
    const DeviceSnapshot& dev = snapshot.devices[0];
    frame.tool.present = true;
    frame.tool.position = dev.position;
    frame.tool.radius = scene.devices[0].tool_radius_m;
    frame.proxy = dev.proxy;
    frame.force = dev.force;
    const double f = std::sqrt(dev.force[0] * dev.force[0] + dev.force[1] * dev.force[1] +
                               dev.force[2] * dev.force[2]);
    std::snprintf(line, sizeof line, "%s: force %.2f N%s", scene.devices[0].name.c_str(), f,
                  dev.contact ? " (contact)" : "");
    frame.overlay_lines.emplace_back(line);
    if (dev.contact) frame.contacts.push_back({dev.proxy, {0, 1, 0}});
  }
  return frame;
}

std::string models_label(const Snapshot& snapshot) {
  std::vector<std::string> names;
  for (const BodySnapshot& b : snapshot.bodies)
    if (std::find(names.begin(), names.end(), b.model) == names.end()) names.push_back(b.model);
  std::string label = names.size() > 1 ? "models: " : "model: ";
  for (size_t i = 0; i < names.size(); ++i) label += (i > 0 ? ", " : "") + names[i];
  return label;
}

Image write_snapshot_png(HeadlessRenderer& renderer, const SceneStatic& scene,
                         const Snapshot& snapshot, const std::string& path, SnapshotStyle style) {
  if (style.model_label.empty()) style.model_label = models_label(snapshot);
  Image image = renderer.render(make_render_frame(scene, snapshot, style));
  const std::filesystem::path file(path);
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  write_png(file, image);
  return image;
}

namespace {

class PngFrameWriter final : public FrameObserver {
 public:
  PngFrameWriter(std::string directory, std::vector<double> times, int width, int height)
      : directory_(std::move(directory)), times_(std::move(times)), width_(width), height_(height) {
    std::sort(times_.begin(), times_.end());
  }

  void on_frame(const SceneStatic& scene, const Snapshot& snapshot) override {
    if (!times_.empty()) {
      // A chosen time is taken by the first snapshot at or after it.
      if (next_ >= times_.size() || snapshot.time_s + 1e-9 < times_[next_]) return;
      while (next_ < times_.size() && snapshot.time_s + 1e-9 >= times_[next_]) ++next_;
    }
    if (!renderer_) {
      // Made here, on the render task's thread, which then owns the GL context.
      renderer_ = std::make_unique<HeadlessRenderer>(HeadlessOptions{width_, height_, true});
      std::filesystem::create_directories(directory_);
    }
    char name[64];
    std::snprintf(name, sizeof name, "/frame_%08.0f.png", snapshot.time_s * 1e3);
    const std::string path = directory_ + name;
    write_png(path, renderer_->render(make_render_frame(scene, snapshot)));
    written_.push_back(path);
  }

  std::vector<std::string> finish() override {
    renderer_.reset();
    return written_;
  }

 private:
  std::string directory_;
  std::vector<double> times_;
  size_t next_ = 0;
  int width_, height_;
  std::unique_ptr<HeadlessRenderer> renderer_;
  std::vector<std::string> written_;
};

}  // namespace

std::unique_ptr<FrameObserver> make_png_frame_writer(const std::string& directory,
                                                     std::vector<double> times, int width,
                                                     int height) {
  return std::make_unique<PngFrameWriter>(directory, std::move(times), width, height);
}

}  // namespace tacta::render
