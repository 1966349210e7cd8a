#include "mouse_tool.hpp"

namespace tacta::view {

void MouseTool::set_target(const Vec3d& target) {
  target_ = target;
  feed(target_);
}

void MouseTool::feed(const Vec3d& target) const {
  if (feed_) feed_(target);
}

void MouseTool::set_buttons(uint32_t buttons) {
  buttons_ = buttons;
  const double values[4] = {target_[0], target_[1], target_[2], static_cast<double>(buttons)};
  if (feed_) feed_(values);
}

void MouseTool::update(const PointerState& pointer, const Camera& camera,
                       const Viewport& viewport) {
  const bool pressed = pointer.left_down && !was_down_;
  was_down_ = pointer.left_down;
  if (!pointer.left_down) dragging_ = false;
  const Vec3d forward = camera_forward(camera);
  if (pressed && !pointer.over_gui) {
    plane_anchor_ = target_;
    plane_normal_ = forward;
    const auto grabbed = intersect_facing_plane(pixel_ray(camera, viewport, pointer.x, pointer.y),
                                                plane_anchor_, plane_normal_);
    if (grabbed) {
      dragging_ = true;
      for (int i = 0; i < 3; ++i) grab_offset_[i] = target_[i] - (*grabbed)[i];
    }
  } else if (dragging_) {
    const auto hit = intersect_facing_plane(pixel_ray(camera, viewport, pointer.x, pointer.y),
                                            plane_anchor_, plane_normal_);
    if (hit)
      set_target(
          {(*hit)[0] + grab_offset_[0], (*hit)[1] + grab_offset_[1], (*hit)[2] + grab_offset_[2]});
  }
  if (pointer.wheel != 0 && !pointer.over_gui) {
    const double d = pointer.wheel * depth_step_m_;
    set_target(
        {target_[0] + d * forward[0], target_[1] + d * forward[1], target_[2] + d * forward[2]});
    plane_anchor_ = target_;  // a drag in progress continues at the new depth
    grab_offset_ = {0, 0, 0};
    if (dragging_) {
      const auto hit = intersect_facing_plane(pixel_ray(camera, viewport, pointer.x, pointer.y),
                                              plane_anchor_, plane_normal_);
      if (hit)
        for (int i = 0; i < 3; ++i) grab_offset_[i] = target_[i] - (*hit)[i];
    }
  }
}

}  // namespace tacta::view
