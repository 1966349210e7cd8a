// The narrow interface through which the god-object proxy asks the world about surfaces. The
// collision layer (plugins, through the engine) answers it; tests answer it with analytic shapes.
// Both queries run in the 1 kHz path: noexcept, no allocation.
#pragma once

#include "tacta/vec3.hpp"

namespace tacta::haptics {

struct SurfaceHit {
  double fraction = 0.0;       // where along the sweep [0, 1] the sphere first touches
  Vec3 point{0.0, 0.0, 0.0};   // m, the touched point on the surface
  Vec3 normal{0.0, 0.0, 1.0};  // unit outward surface normal at point
  int body = -1;               // which body was touched (engine-defined id; -1 unknown)
  int triangle = -1;           // which surface triangle (for barycentric force transfer)
  double barycentric[3] = {0.0, 0.0, 0.0};  // of point in that triangle, when known
};

class SurfaceQuery {
 public:
  virtual ~SurfaceQuery() = default;
  // First contact of a sphere of `radius` (m) swept from `from` to `to` (m) with any surface,
  // approaching from outside. false when the sweep is free.
  virtual bool first_hit(const Vec3& from, const Vec3& to, double radius,
                         SurfaceHit& hit) const noexcept = 0;
  // The surface point closest to `point` within max_distance (m), with the outward normal there.
  // Used to keep the proxy on curved surfaces and to detect a device that starts inside.
  // signed_distance: distance of `point` from the surface, negative inside.
  virtual bool closest_point(const Vec3& point, double max_distance, SurfaceHit& hit,
                             double& signed_distance) const noexcept = 0;
  // True when the answerer knows without a search that `point` is outside every surface and at
  // least `distance` (m) from it (closest_point would find it no nearer): e.g. from where its
  // last closest point was and how far the point and the surfaces have moved since. false: not
  // known, ask closest_point. Lets a proxy in free space skip looking for a surface come onto it.
  virtual bool clear_of(const Vec3& point, double distance) const noexcept {
    (void)point;
    (void)distance;
    return false;
  }
};

}  // namespace tacta::haptics
