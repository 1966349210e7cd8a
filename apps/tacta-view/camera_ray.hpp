// Screen <-> world for the viewer's mouse: a pixel's ray from the camera, a world point's pixel,
// and the drag plane that faces the camera. Same perspective as the renderer (vertical field of
// view, aspect from the viewport). Pixels: x to the right, y down, origin at the top left.
#pragma once

#include <optional>

#include "tacta/render/frame.hpp"

namespace tacta::view {

using render::Camera;
using render::Vec3d;

struct Ray {
  Vec3d origin;     // m, the eye
  Vec3d direction;  // unit
};

struct Viewport {
  double width = 1;   // pixels
  double height = 1;  // pixels
};

// Unit vector from the eye toward the target.
Vec3d camera_forward(const Camera& camera);
Ray pixel_ray(const Camera& camera, const Viewport& viewport, double x, double y);
// The pixel where `point` appears; nullopt when it is behind the eye.
std::optional<std::array<double, 2>> project(const Camera& camera, const Viewport& viewport,
                                             const Vec3d& point);

// A plane through `anchor` with the camera's forward direction as normal: dragging keeps the
// target at the same depth. Returns where the ray meets it (nullopt when parallel or behind).
std::optional<Vec3d> intersect_facing_plane(const Ray& ray, const Vec3d& anchor,
                                            const Vec3d& normal);

}  // namespace tacta::view
