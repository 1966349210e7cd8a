// The mouse as a haptic device: pointer input (real, or scripted in tests) moves the target of
// the `mouse` device plugin. A left drag moves the target on the plane facing the camera through
// the point where the drag began (grab-relative, so it does not jump); the wheel moves it along
// the view direction. The target reaches the device through `feed`: the viewer wires it to
// Simulation::device_input of every mouse device in the scene (the instances the simulation
// owns, each with its own lock-free target). The buttons held (the cut key holding a blade's
// button) go the same way, as the input's fourth value.
#pragma once

#include <cstdint>
#include <functional>
#include <span>

#include "camera_ray.hpp"

namespace tacta::view {

struct PointerState {
  double x = 0, y = 0;  // pixels in the window, top left origin
  bool left_down = false;
  double wheel = 0;       // notches this frame, + away from the viewer
  bool over_gui = false;  // Dear ImGui wants the mouse: the scene ignores it
};

class MouseTool {
 public:
  // The device input: a target x, y, z (m), then with a fourth value the buttons held (a bit
  // mask); three values leave the buttons as they were. Must be safe from any thread.
  using Feed = std::function<void(std::span<const double> values)>;
  explicit MouseTool(Feed feed) : feed_(std::move(feed)) {}
  bool available() const { return static_cast<bool>(feed_); }

  void set_target(const Vec3d& target);  // m, fed to the device at once
  // Feeds a target without remembering it: safe from any thread (the device's slot is lock-free).
  void feed(const Vec3d& target) const;
  const Vec3d& target() const { return target_; }
  // Holds `buttons` (bit i = button i) from now on, fed with the target at once.
  void set_buttons(uint32_t buttons);
  uint32_t buttons() const { return buttons_; }
  void set_depth_step(double metres_per_notch) { depth_step_m_ = metres_per_notch; }
  bool dragging() const { return dragging_; }

  void update(const PointerState& pointer, const Camera& camera, const Viewport& viewport);

 private:
  Feed feed_;
  Vec3d target_{0, 0, 0};
  uint32_t buttons_ = 0;
  double depth_step_m_ = 0.002;  // m per wheel notch
  bool dragging_ = false;
  bool was_down_ = false;
  Vec3d plane_anchor_{0, 0, 0}, plane_normal_{0, 0, 1};
  Vec3d grab_offset_{0, 0, 0};  // target minus the grabbed point on the plane, m
};

}  // namespace tacta::view
