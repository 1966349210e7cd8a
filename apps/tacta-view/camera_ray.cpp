#include "camera_ray.hpp"

#include <cmath>

#include "tacta/vec3.hpp"

namespace tacta::view {
namespace {

// The camera's direction when eye and target coincide: down -z, as the default view looks.
Vec3d normalised(const Vec3d& v) { return normalized(v, {0, 0, -1}); }

struct Basis {
  Vec3d forward, right, up;
  double tan_half_fov;
};

Basis basis(const Camera& camera) {
  Basis b;
  b.forward = camera_forward(camera);
  b.right = normalised(cross(b.forward, camera.up));
  b.up = cross(b.right, b.forward);
  b.tan_half_fov = std::tan(camera.vertical_fov_rad / 2);
  return b;
}

}  // namespace

Vec3d camera_forward(const Camera& camera) { return normalised(sub(camera.target, camera.eye)); }

Ray pixel_ray(const Camera& camera, const Viewport& viewport, double x, double y) {
  const Basis b = basis(camera);
  const double aspect = viewport.width / viewport.height;
  const double ndc_x = 2 * x / viewport.width - 1;   // -1 left, +1 right
  const double ndc_y = 1 - 2 * y / viewport.height;  // -1 bottom, +1 top
  Vec3d d = add_scaled(b.forward, b.right, ndc_x * b.tan_half_fov * aspect);
  d = add_scaled(d, b.up, ndc_y * b.tan_half_fov);
  return {camera.eye, normalised(d)};
}

std::optional<std::array<double, 2>> project(const Camera& camera, const Viewport& viewport,
                                             const Vec3d& point) {
  const Basis b = basis(camera);
  const Vec3d v = sub(point, camera.eye);
  const double depth = dot(v, b.forward);
  if (depth <= 0) return std::nullopt;
  const double aspect = viewport.width / viewport.height;
  const double ndc_x = dot(v, b.right) / (depth * b.tan_half_fov * aspect);
  const double ndc_y = dot(v, b.up) / (depth * b.tan_half_fov);
  return std::array<double, 2>{(ndc_x + 1) * viewport.width / 2, (1 - ndc_y) * viewport.height / 2};
}

std::optional<Vec3d> intersect_facing_plane(const Ray& ray, const Vec3d& anchor,
                                            const Vec3d& normal) {
  const double along = dot(ray.direction, normal);
  if (std::abs(along) < 1e-9) return std::nullopt;
  const double t = dot(sub(anchor, ray.origin), normal) / along;
  if (t <= 0) return std::nullopt;
  return add_scaled(ray.origin, ray.direction, t);
}

}  // namespace tacta::view
