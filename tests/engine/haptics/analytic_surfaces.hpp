// Analytic surfaces answering the god-object's SurfaceQuery: a plane and a sphere, exact, so the
// proxy can be checked against closed-form answers.
#pragma once

#include <cmath>

#include "tacta/haptics/surface_query.hpp"

namespace tacta::haptics::testing {

// The half-space below the plane through `origin` with unit outward normal `normal` is solid.
class PlaneSurface : public SurfaceQuery {
 public:
  PlaneSurface(const Vec3& origin, const Vec3& normal)
      : origin_(origin), normal_(scaled(normal, 1.0 / norm(normal))) {}
  bool first_hit(const Vec3& from, const Vec3& to, double radius,
                 SurfaceHit& hit) const noexcept override {
    const double d_from = dot(sub(from, origin_), normal_) - radius;
    const double d_to = dot(sub(to, origin_), normal_) - radius;
    if (d_from < 0.0 || d_to >= 0.0) return false;  // starts inside, or never reaches it
    hit.fraction = d_from / (d_from - d_to);
    const Vec3 centre = add_scaled(from, sub(to, from), hit.fraction);
    hit.point = add_scaled(centre, normal_, -radius);
    hit.normal = normal_;
    return true;
  }
  bool closest_point(const Vec3& point, double max_distance, SurfaceHit& hit,
                     double& signed_distance) const noexcept override {
    signed_distance = dot(sub(point, origin_), normal_);
    if (std::abs(signed_distance) > max_distance) return false;
    hit.point = add_scaled(point, normal_, -signed_distance);
    hit.normal = normal_;
    hit.fraction = 0.0;
    return true;
  }
  void set_origin(const Vec3& origin) { origin_ = origin; }

 private:
  Vec3 origin_;
  Vec3 normal_;
};

// A solid ball of radius `radius` at `centre`.
class SphereSurface : public SurfaceQuery {
 public:
  SphereSurface(const Vec3& centre, double radius) : centre_(centre), radius_(radius) {}
  bool first_hit(const Vec3& from, const Vec3& to, double radius,
                 SurfaceHit& hit) const noexcept override {
    // |from + s d - c| = R + r, first root s in [0, 1] with `from` outside.
    const double reach = radius_ + radius;
    const Vec3 d = sub(to, from);
    const Vec3 m = sub(from, centre_);
    const double c = dot(m, m) - reach * reach;
    if (c < 0.0) return false;  // starts inside
    const double a = dot(d, d);
    const double b = dot(m, d);
    const double discriminant = b * b - a * c;
    if (a <= 0.0 || b >= 0.0 || discriminant < 0.0) return false;
    const double s = (-b - std::sqrt(discriminant)) / a;
    if (s < 0.0 || s > 1.0) return false;
    const Vec3 at = add_scaled(from, d, s);
    hit.fraction = s;
    hit.normal = scaled(sub(at, centre_), 1.0 / norm(sub(at, centre_)));
    hit.point = add_scaled(centre_, hit.normal, radius_);
    return true;
  }
  bool closest_point(const Vec3& point, double max_distance, SurfaceHit& hit,
                     double& signed_distance) const noexcept override {
    const Vec3 offset = sub(point, centre_);
    const double length = norm(offset);
    signed_distance = length - radius_;
    if (std::abs(signed_distance) > max_distance) return false;
    hit.normal = length > 0.0 ? scaled(offset, 1.0 / length) : Vec3{0.0, 0.0, 1.0};
    hit.point = add_scaled(centre_, hit.normal, radius_);
    hit.fraction = 0.0;
    return true;
  }

 private:
  Vec3 centre_;
  double radius_;
};

}  // namespace tacta::haptics::testing
