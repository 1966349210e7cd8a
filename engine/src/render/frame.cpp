#include "tacta/render/frame.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "math.hpp"

namespace tacta::render {

using namespace detail;

namespace {

struct BoundsBuilder {
  Vec3d min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
            std::numeric_limits<double>::infinity()};
  Vec3d max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
            -std::numeric_limits<double>::infinity()};
  bool any = false;
  void add(const Vec3d& p, double pad = 0) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) return;
    for (size_t k = 0; k < 3; ++k) {
      min[k] = std::min(min[k], p[k] - pad);
      max[k] = std::max(max[k], p[k] + pad);
    }
    any = true;
  }
};

}  // namespace

Bounds frame_bounds(const RenderFrame& frame) {
  BoundsBuilder b;
  for (const BodyDraw& body : frame.bodies)
    for (size_t i = 0; i + 2 < body.positions.size(); i += 3)
      b.add({body.positions[i], body.positions[i + 1], body.positions[i + 2]});
  if (frame.tool.present) {
    if (frame.tool.mesh && !frame.tool.mesh->positions.empty()) {
      const std::vector<double>& local = frame.tool.mesh->positions;  // m, tool frame
      for (size_t i = 0; i + 2 < local.size(); i += 3)
        b.add(add(frame.tool.position, rotate(unit_quaternion(frame.tool.orientation),
                                              {local[i], local[i + 1], local[i + 2]})));
    } else {
      b.add(frame.tool.position, frame.tool.radius);
    }
  }
  if (frame.proxy) b.add(*frame.proxy);
  if (!b.any) return {{-0.5, -0.5, -0.5}, {0.5, 0.5, 0.5}};
  return {b.min, b.max};
}

void fit_camera(RenderFrame& frame, const Vec3d& view_direction) {
  const Bounds bounds = frame_bounds(frame);
  const Vec3d centre = scaled(add(bounds.min, bounds.max), 0.5);
  const double radius = std::max(0.5 * norm(sub(bounds.max, bounds.min)), 1e-4);
  const double half_fov = std::clamp(frame.camera.vertical_fov_rad, 0.05, 3.0) / 2;
  const double distance = 1.05 * radius / std::sin(half_fov);  // the bounding sphere just fits
  const Vec3d direction = normalized(view_direction, {0, 0, 1});
  frame.camera.target = centre;
  frame.camera.eye = add(centre, scaled(direction, distance));
  frame.camera.up = std::fabs(direction[1]) > 0.999 ? Vec3d{0, 0, -1} : Vec3d{0, 1, 0};
}

}  // namespace tacta::render
