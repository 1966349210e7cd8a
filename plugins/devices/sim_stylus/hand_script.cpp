#include "hand_script.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace tacta::sim_stylus {
namespace {

// C1 ease from 0 to 1 over u in [0, 1]: the hand starts and stops without a velocity jump.
double smooth(double u) noexcept {
  u = std::clamp(u, 0.0, 1.0);
  return u * u * (3.0 - 2.0 * u);
}
Point lerp(const Point& a, const Point& b, double s) noexcept {
  return {a[0] + (b[0] - a[0]) * s, a[1] + (b[1] - a[1]) * s, a[2] + (b[2] - a[2]) * s};
}
double distance(const Point& a, const Point& b) noexcept {
  return std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
}
void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("sim_stylus: " + what);
}

}  // namespace

HandScript::HandScript(const ScriptSettings& settings)
    : settings_(settings),
      waypoints_(settings.waypoints.begin(), settings.waypoints.end()),
      points_(settings.palpation_points.begin(), settings.palpation_points.end()) {
  settings_.waypoints = {};
  settings_.palpation_points = {};
  const double axis_length =
      std::hypot(settings.approach_axis[0], settings.approach_axis[1], settings.approach_axis[2]);
  require(axis_length > 1e-9,
          "approach_axis must be a non-zero vector (a direction out of the surface)");
  for (double& c : settings_.approach_axis) c /= axis_length;
  switch (settings.pattern) {
    case Pattern::waypoints:
      if (waypoints_.empty()) {  // no script: the hand holds the stylus at its rest position
        const Point& r = settings.rest_position;
        waypoints_ = {0.0, r[0], r[1], r[2]};
      }
      require(waypoints_.size() % 4 == 0,
              "pattern 'waypoints' expects waypoints as groups of 4 numbers (t s, x y z m)");
      for (size_t i = 4; i < waypoints_.size(); i += 4)
        require(
            waypoints_[i] >= waypoints_[i - 4],
            "waypoint " + std::to_string(i / 4) + ": expected a time not before the previous one");
      duration_ = waypoints_[waypoints_.size() - 4];
      break;
    case Pattern::tap:
      require(settings.tap_period > 0.0, "pattern 'tap' expects tap_period > 0 s");
      duration_ = std::numeric_limits<double>::infinity();
      break;
    case Pattern::stroke: {
      require(settings.stroke_speed > 0.0, "pattern 'stroke' expects stroke_speed > 0 m/s");
      const double vertical = (settings.approach_height + settings.depth) / settings.stroke_speed;
      duration_ = 2.0 * vertical +
                  distance(settings.stroke_start, settings.stroke_end) / settings.stroke_speed;
      break;
    }
    case Pattern::palpation:
      require(points_.size() >= 3 && points_.size() % 3 == 0,
              "pattern 'palpation' expects palpation_points as groups of 3 numbers (x y z m), at "
              "least one");
      require(settings.press_duration > 0.0, "pattern 'palpation' expects press_duration > 0 s");
      duration_ =
          static_cast<double>(points_.size() / 3) *
          (settings.travel_duration + 2.0 * settings.press_duration + settings.dwell_duration);
      break;
  }
}

Point HandScript::above(const Point& p) const noexcept {
  return lerp(p,
              {p[0] + settings_.approach_axis[0], p[1] + settings_.approach_axis[1],
               p[2] + settings_.approach_axis[2]},
              settings_.approach_height);
}
Point HandScript::below(const Point& p) const noexcept {
  return lerp(p,
              {p[0] - settings_.approach_axis[0], p[1] - settings_.approach_axis[1],
               p[2] - settings_.approach_axis[2]},
              settings_.depth);
}

Point HandScript::target(double time) const noexcept {
  switch (settings_.pattern) {
    case Pattern::waypoints: return waypoint_target(time);
    case Pattern::tap: {
      const double phase =
          std::fmod(std::max(time, 0.0), settings_.tap_period) / settings_.tap_period;
      // Raised cosine: down from approach height to depth and back once per period.
      const double s = 0.5 * (1.0 - std::cos(2.0 * std::numbers::pi * phase));
      return lerp(above(settings_.tap_point), below(settings_.tap_point), s);
    }
    case Pattern::stroke: return stroke_target(time);
    case Pattern::palpation: return palpation_target(time);
  }
  return {0.0, 0.0, 0.0};
}

Point HandScript::waypoint_target(double time) const noexcept {
  const size_t count = waypoints_.size() / 4;
  auto at = [&](size_t i) {
    return Point{waypoints_[4 * i + 1], waypoints_[4 * i + 2], waypoints_[4 * i + 3]};
  };
  if (time <= waypoints_[0]) return at(0);
  for (size_t i = 1; i < count; ++i) {
    const double t0 = waypoints_[4 * (i - 1)];
    const double t1 = waypoints_[4 * i];
    if (time < t1) return lerp(at(i - 1), at(i), (time - t0) / (t1 - t0));  // t1 > t0 here
  }
  return at(count - 1);
}

Point HandScript::stroke_target(double time) const noexcept {
  const double vertical = (settings_.approach_height + settings_.depth) / settings_.stroke_speed;
  const double along =
      distance(settings_.stroke_start, settings_.stroke_end) / settings_.stroke_speed;
  const Point start_down = below(settings_.stroke_start);
  const Point end_down = below(settings_.stroke_end);
  if (time < vertical)
    return lerp(above(settings_.stroke_start), start_down, smooth(time / vertical));
  if (time < vertical + along) return lerp(start_down, end_down, (time - vertical) / along);
  return lerp(end_down, above(settings_.stroke_end), smooth((time - vertical - along) / vertical));
}

Point HandScript::palpation_target(double time) const noexcept {
  const size_t count = points_.size() / 3;
  const double travel = settings_.travel_duration;
  const double press = settings_.press_duration;
  const double block = travel + 2.0 * press + settings_.dwell_duration;
  auto point = [&](size_t i) {
    return Point{points_[3 * i], points_[3 * i + 1], points_[3 * i + 2]};
  };
  if (time <= 0.0) return above(point(0));
  // Repeating, each cycle after the first starts with the travel from the last point back to the first.
  const double cycle = static_cast<double>(count) * block;
  const bool wrapped = settings_.palpation_repeat && time >= cycle;
  if (settings_.palpation_repeat) time = std::fmod(time, cycle);
  const size_t i = std::min(static_cast<size_t>(time / block), count - 1);
  const Point p = point(i);
  double local = time - static_cast<double>(i) * block;
  const size_t from = i > 0 ? i - 1 : (wrapped ? count - 1 : 0);
  if (local < travel) return lerp(above(point(from)), above(p), smooth(local / travel));
  local -= travel;
  if (local < press) return lerp(above(p), below(p), smooth(local / press));
  local -= press;
  if (local < settings_.dwell_duration) return below(p);
  local -= settings_.dwell_duration;
  return lerp(below(p), above(p), smooth(local / press));
}

}  // namespace tacta::sim_stylus
