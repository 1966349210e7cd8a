// The scripted hand's target trajectory (m, world frame) for the sim_stylus patterns. Built once
// at create (may throw std::invalid_argument), then evaluated in the 1 kHz path (noexcept, no
// allocation).
#pragma once

#include <array>
#include <span>
#include <vector>

namespace tacta::sim_stylus {

using Point = std::array<double, 3>;

enum class Pattern { waypoints = 0, tap = 1, stroke = 2, palpation = 3 };

struct ScriptSettings {
  Pattern pattern = Pattern::waypoints;
  std::span<const double> waypoints;         // t x y z, stride 4 (s, m); empty: hold at rest
  Point rest_position{0.0, 0.0, 0.0};        // m, where the hand holds with no waypoints
  Point approach_axis{0.0, 1.0, 0.0};        // unit, pointing out of the surface toward the hand
  double approach_height = 0.01;             // m above a press point where the hand starts/returns
  double depth = 0.005;                      // m the target goes below a press point
  Point tap_point{0.0, 0.0, 0.0};            // m
  double tap_period = 0.5;                   // s
  Point stroke_start{0.0, 0.0, 0.0};         // m
  Point stroke_end{0.0, 0.0, 0.0};           // m
  double stroke_speed = 0.02;                // m/s
  std::span<const double> palpation_points;  // x y z, stride 3 (m)
  double travel_duration = 0.5;              // s between points, at approach height
  double press_duration = 0.3;               // s to go down (and again to come up)
  double dwell_duration = 0.5;               // s held at depth
  bool palpation_repeat = false;             // after the last point, back to the first, forever
};

class HandScript {
 public:
  explicit HandScript(const ScriptSettings& settings);    // validates; throws std::invalid_argument
  Point target(double time) const noexcept;               // m
  double duration() const noexcept { return duration_; }  // s, after which the target holds

 private:
  Point above(const Point& p) const noexcept;
  Point below(const Point& p) const noexcept;
  Point waypoint_target(double time) const noexcept;
  Point palpation_target(double time) const noexcept;
  Point stroke_target(double time) const noexcept;
  ScriptSettings settings_;
  std::vector<double> waypoints_;  // copies: the parameter arrays may not outlive create()
  std::vector<double> points_;
  double duration_ = 0.0;
};

}  // namespace tacta::sim_stylus
