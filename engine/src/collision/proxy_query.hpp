// CollisionContext's answers to the god-object proxy's queries (haptics::SurfaceQuery): the
// proxy plugin's sphere cast and closest point over each present surface, each made ready by
// prepare_query (margin, vertices made current, the patch near the tool), and what the last
// closest points (or the slices' boxes) tell without a search (clear_of). Included by
// collision_context.cpp only.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>

#include "collision/collision_context.hpp"
#include "collision/collision_instance.hpp"
#include "tacta/haptics/surface_query.hpp"

namespace tacta {

// The proxy's view of the surfaces: the first instance that answers sphere casts and closest
// points, over one body's surface or all of them.
class CollisionContext::Query final : public haptics::SurfaceQuery {
 public:
  Query(CollisionContext& context, const CollisionInstance* answerer)
      : context_(context), answerer_(answerer) {}
  void restrict_to(int surface) { surface_ = surface; }

  bool first_hit(const Vec3& from, const Vec3& to, double radius,
                 haptics::SurfaceHit& hit) const noexcept override {
    if (answerer_ == nullptr || answerer_->api.sphere_cast == nullptr) return false;
    const Timed timed(context_);
    bool found = false;
    for (uint32_t s = 0; s < context_.view_.surface_count; ++s) {
      if (!asked(s)) continue;
      Vec3 lo, hi;
      for (size_t a = 0; a < 3; ++a) {
        lo[a] = std::min(from[a], to[a]) - radius;
        hi[a] = std::max(from[a], to[a]) + radius;
      }
      context_.prepare_query(s, lo, hi);
      tacta_surface_hit h{};
      if (answerer_->api.sphere_cast(answerer_->instance, &context_.view_, s, from.data(),
                                     to.data(), radius, &h) &&
          (!found || h.toi < hit.fraction)) {
        fill(hit, h, s);
        hit.fraction = h.toi;
        found = true;
      }
    }
    return found;
  }

  bool closest_point(const Vec3& point, double max_distance, haptics::SurfaceHit& hit,
                     double& signed_distance) const noexcept override {
    if (answerer_ == nullptr || answerer_->api.closest_point == nullptr) return false;
    const Timed timed(context_);
    bool found = false;
    for (uint32_t s = 0; s < context_.view_.surface_count; ++s) {
      if (!asked(s)) continue;
      // A surface brought up to date only where queries look is searched in growing balls, the
      // first 10 % past the distance the last query on it found (the surface and the tool move
      // far less in a tick): the patch made current is about that ball's, and its area grows
      // with the ball's square (25 % past cost 3k instructions a tick more on the demo). A point
      // found within a ball is the closest: anything nearer was in it.
      double reach = max_distance;
      if (context_.patched(s) && max_distance > 0 && std::isfinite(context_.last_distance_[s]))
        reach = std::clamp(1.1 * context_.last_distance_[s], 0.05 * max_distance, max_distance);
      tacta_surface_hit h{};
      bool hit_here = false;
      for (;;) {
        const Vec3 lo{point[0] - reach, point[1] - reach, point[2] - reach};
        const Vec3 hi{point[0] + reach, point[1] + reach, point[2] + reach};
        context_.prepare_query(s, lo, hi);
        hit_here = answerer_->api.closest_point(answerer_->instance, &context_.view_, s,
                                                point.data(), reach, &h) != 0;
        if (hit_here || !(reach < max_distance)) break;
        reach = std::min(2.0 * reach, max_distance);
      }
      context_.last_distance_[s] =
          hit_here && std::isfinite(h.distance) ? h.distance : max_distance;
      Sighting& seen = context_.sightings_[s];
      seen.outside = false;  // until known below
      if (!hit_here) continue;
      const double side = (point[0] - h.point[0]) * h.normal[0] +
                          (point[1] - h.point[1]) * h.normal[1] +
                          (point[2] - h.point[2]) * h.normal[2];
      if (context_.sliced_ && side >= 0)
        seen = {point, h.distance, context_.freshness_[s].odometer_base(), true};
      if (found && h.distance >= std::fabs(signed_distance)) continue;
      fill(hit, h, s);
      hit.fraction = 0;
      signed_distance = side < 0 ? -h.distance : h.distance;
      found = true;
    }
    return found;
  }

  // Each surface's last closest point was found outside it, and since then neither the point
  // nor the surface can have closed the distance to below `distance`: the point has moved by
  // |point - then|, no vertex by more than the surface's odometer since. Where they may have,
  // but not to zero (the point is still outside), the slices' boxes may tell (bounded_clear).
  bool clear_of(const Vec3& point, double distance) const noexcept override {
    if (!context_.sliced_) return false;
    bool any = false;
    uint64_t bounded = 0;  // surfaces the boxes answered for
    for (uint32_t s = 0; s < context_.view_.surface_count; ++s) {
      if (!asked(s)) continue;
      const Sighting& seen = context_.sightings_[s];
      if (!seen.outside) return false;
      const double moved =
          norm(sub(point, seen.point)) + (context_.freshness_[s].odometer() - seen.odometer_base);
      const double left = seen.distance - moved;  // NaN: not known
      if (!(left >= distance)) {
        if (!(left > 0.0 && bounded_clear(s, point, distance))) return false;
        bounded = 1;
      }
      any = true;
    }
    context_.clear_answers_ += any ? 1 : 0;
    context_.clear_bound_answers_ += any ? bounded : 0;
    return any;
  }

 private:
  // Surface s, which `point` is outside, is no nearer to it than `distance` by its slices' boxes
  // grown by how far each slice's vertices may have moved (SurfaceFreshness::clearance), found
  // up to kClearanceLimit x distance: a new sighting. A few dozen boxes, where closest_point
  // would make current and test every fine triangle within its ball (60-100 on the liver demo,
  // 10-40 us).
  bool bounded_clear(uint32_t s, const Vec3& point, double distance) const noexcept {
    const Timed timed(context_);
    const double bound = context_.freshness_[s].clearance(point.data(), kClearanceLimit * distance);
    if (!(bound >= distance)) return false;
    context_.sightings_[s] = {point, bound, context_.freshness_[s].odometer_base(), true};
    return true;
  }
  // Surface s is one this query answers for: present, and the one it is restricted to, if any.
  bool asked(uint32_t s) const noexcept {
    return (surface_ < 0 || static_cast<uint32_t>(surface_) == s) && context_.surface_present(s);
  }
  // Adds a query's wall time to the context's query_ms and leaves the view's margin at 0 (and
  // its make_current unset: other callers read every position as current).
  struct Timed {
    explicit Timed(CollisionContext& c) : context(c), start(std::chrono::steady_clock::now()) {}
    ~Timed() {
      context.view_.query_margin = 0.0;
      context.view_.make_current = nullptr;
      context.view_.proxy_candidates = nullptr;
      context.view_.proxy_candidate_count = 0;
      context.query_ms_ +=
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
    }
    CollisionContext& context;
    std::chrono::steady_clock::time_point start;
  };
  void fill(haptics::SurfaceHit& out, const tacta_surface_hit& h, uint32_t surface) const noexcept {
    for (int a = 0; a < 3; ++a) {
      out.point[static_cast<size_t>(a)] = h.point[a];
      out.normal[static_cast<size_t>(a)] = h.normal[a];
      out.barycentric[a] = h.barycentric[a];
    }
    out.body = context_.body_of(surface);
    out.triangle = static_cast<int>(h.triangle);
  }
  // How far bounded_clear searches, in units of the distance asked (the tool's radius): a bound
  // up to this leaves the point that many radii less one to travel before the next check.
  static constexpr double kClearanceLimit = 4.0;
  CollisionContext& context_;
  const CollisionInstance* answerer_;
  int surface_ = -1;
};

}  // namespace tacta
