// sim_stylus: a simulated Phantom Omni class stylus held by a scripted hand.
//
// The hand is an impedance: a spring (hand_stiffness) and damper (hand_damping) pull the stylus,
// a point mass (hand_mass: stylus plus the hand's effective mass), toward the script's target;
// the force written to the device acts on the same mass, so the rendered force pushes back on
// the motion (closed loop). read(time) integrates from the previous read to `time` with the last
// written force held (zero-order hold, as a real amplifier), semi-implicit Euler in sub-steps
// short enough for the hand spring. Device numbers (workspace about 160 x 120 x 70 mm, peak
// 3.3 N, continuous about 0.88 N, usable stiffness about 1 N/mm at 1 kHz) from
// docs/REFERENCES.md; hand mass, stiffness and damping defaults are modelling
// assumptions (the damping is critical for the default mass and stiffness).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "button_schedule.hpp"
#include "hand_script.hpp"
#include "tacta/sdk/device.hpp"
#include "tacta_devices/omni_profile.hpp"
#include "tacta_devices/state_bytes.hpp"

namespace tacta::sim_stylus {
namespace {

constexpr double kTeleportGap = 1.0;  // s; a longer gap between reads restarts at the target
constexpr int kMaxSubsteps = 100000;

// splitmix64 and Box-Muller: the same seed gives the same noise on every platform and library.
class GaussianNoise {
 public:
  explicit GaussianNoise(uint64_t seed) noexcept : state_(seed) {}
  double next() noexcept {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double u1 = (static_cast<double>(bits() >> 11) + 1.0) * 0x1.0p-53;  // (0, 1]
    const double u2 = static_cast<double>(bits() >> 11) * 0x1.0p-53;          // [0, 1)
    const double radius = std::sqrt(-2.0 * std::log(u1));
    spare_ = radius * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return radius * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  uint64_t bits() noexcept {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  uint64_t state_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

Point to_point(std::span<const double> v, Point fallback) {
  return v.size() >= 3 ? Point{v[0], v[1], v[2]} : fallback;
}

}  // namespace

class SimStylus {
 public:
  static constexpr const char* kName = "sim_stylus";
  static constexpr const char* kDescription =
      "Simulated Phantom Omni class stylus moved by a scripted hand impedance (closed loop)";
  static constexpr uint32_t kVersion = 10000;
  static constexpr double kBig = 1e6;
  static constexpr std::array<tacta_param_spec, 23> kParams{{
      sdk::vector_param("workspace_origin", "m", 3, "0 0 0", -kBig, kBig,
                        "centre of the device workspace in the world"),
      sdk::choice_param("pattern", "waypoints|tap|stroke|palpation", 0,
                        "what the scripted hand does"),
      sdk::vector_param("waypoints", "s, m", 4, "", -kBig, kBig,
                        "t x y z per waypoint (world), linear between, held after the last; none: "
                        "rest at workspace_origin"),
      sdk::vector_param("approach_axis", "", 3, "0 1 0", -1.0, 1.0,
                        "direction out of the surface, toward the hand"),
      sdk::real_param("approach_height", "m", 0.01, 0.0, 0.2,
                      "height above a press point where the hand hovers"),
      sdk::real_param("depth", "m", 0.005, 0.0, 0.1, "how far below a press point the hand aims"),
      sdk::vector_param("tap_point", "m", 3, "0 0 0", -kBig, kBig, "tap: surface point tapped"),
      sdk::real_param("tap_period", "s", 0.5, 0.01, 100.0, "tap: one tap (down and up) per period"),
      sdk::vector_param("stroke_start", "m", 3, "0 0 0", -kBig, kBig,
                        "stroke: surface point where it starts"),
      sdk::vector_param("stroke_end", "m", 3, "0.02 0 0", -kBig, kBig,
                        "stroke: surface point where it ends"),
      sdk::real_param("stroke_speed", "m/s", 0.02, 1e-4, 1.0, "stroke: hand speed"),
      sdk::vector_param("palpation_points", "m", 3, "0 0 0", -kBig, kBig,
                        "palpation: surface points pressed in turn"),
      sdk::real_param("travel_duration", "s", 0.5, 0.0, 100.0,
                      "palpation: time to move between points"),
      sdk::real_param("press_duration", "s", 0.3, 0.001, 100.0,
                      "palpation: time to press down (and to release)"),
      sdk::real_param("dwell_duration", "s", 0.5, 0.0, 100.0, "palpation: time held at depth"),
      sdk::real_param("hand_mass", "kg", 0.1, 1e-3, 10.0, "stylus plus hand effective mass"),
      sdk::real_param("hand_stiffness", "N/m", 300.0, 0.0, 1e5, "hand spring toward the target"),
      sdk::real_param("hand_damping", "N s/m", 11.0, 0.0, 1e4,
                      "hand damper on the velocity relative to the target"),
      sdk::real_param("encoder_resolution", "m", 0.0, 0.0, 0.01,
                      "position quantisation step; 0 = off"),
      sdk::real_param("noise_std", "m", 0.0, 0.0, 0.01,
                      "position noise standard deviation, seeded by the scene seed"),
      sdk::bool_param("limit_to_workspace", true,
                      "the stylus stops at the workspace box, as at a mechanical limit"),
      sdk::bool_param("palpation_repeat", false,
                      "palpation: after the last point, travel back to the first and start over"),
      sdk::vector_param("button_times", "s", 2, "", -kBig, kBig,
                        "press, release, press, release, ... ascending: button 0 is held from "
                        "each press until its release (a blade tool cuts while it is held)"),
  }};

  explicit SimStylus(const tacta_device_setup& setup)
      : params_(kParams, setup.params, setup.param_count),
        origin_(to_point(params_.vector("workspace_origin"), {0, 0, 0})),
        script_(settings()),
        button_schedule_(params_.vector("button_times")),
        mass_(params_.real("hand_mass")),
        stiffness_(params_.real("hand_stiffness")),
        damping_(params_.real("hand_damping")),
        resolution_(params_.real("encoder_resolution")),
        noise_std_(params_.real("noise_std")),
        limit_to_workspace_(params_.flag("limit_to_workspace")),
        noise_(setup.seed) {
    if (!(mass_ > 0.0)) throw std::invalid_argument("sim_stylus: hand_mass must be > 0 kg");
    // Sub-step: a fifth of the hand spring's 1/omega and half its damping time, at most 0.1 ms.
    max_substep_ = 1e-4;
    if (stiffness_ > 0.0)
      max_substep_ = std::min(max_substep_, 0.2 * std::sqrt(mass_ / stiffness_));
    if (damping_ > 0.0) max_substep_ = std::min(max_substep_, 0.5 * mass_ / damping_);
  }

  void connect() { connected_ = true; }
  void disconnect() noexcept { connected_ = false; }

  tacta_device_state read(double time, tacta_device_sample& sample) noexcept {
    if (!connected_) {
      fill(time, sample);
      return TACTA_DEVICE_DISCONNECTED;
    }
    if (!started_ || !(time - last_time_ <= kTeleportGap)) {
      // First read, or a gap too long to integrate: the stylus starts at rest on the target.
      position_ = script_.target(time);
      velocity_ = {0.0, 0.0, 0.0};
      if (limit_to_workspace_)
        for (int i = 0; i < 3; ++i)
          devices::stop_at_workspace(origin_, static_cast<size_t>(i), position_, velocity_);
      started_ = true;
      last_time_ = time;
    } else if (time > last_time_) {
      integrate(last_time_, time);
      last_time_ = time;
    }  // time going backwards: the state stays as it is
    fill(time, sample);
    return TACTA_DEVICE_CONNECTED;
  }

  void write(double, const tacta_device_command& command) noexcept {
    force_ = devices::saturate_force(command.force);
  }

  tacta_device_capabilities capabilities() const noexcept {
    // sim_stylus: 6 sensed (the Omni senses its gimbal; here the orientation stays the identity).
    return devices::omni_capabilities(origin_, 6);
  }

  // Checkpoints: the hand's motion, the force it holds and the noise generator.
  size_t save_state(void* bytes, size_t capacity) const noexcept {
    return devices::save_fields(bytes, capacity, started_, last_time_, position_, velocity_, force_,
                                noise_);
  }
  void load_state(const void* bytes, size_t size) {
    devices::load_fields("sim_stylus", bytes, size, started_, last_time_, position_, velocity_,
                         force_, noise_);
  }

  tacta_device_state status(char* reason, size_t capacity) const noexcept {
    sdk::write_message(
        reason, capacity,
        connected_ ? "connected" : "not connected (connect() not called or disconnected)");
    return connected_ ? TACTA_DEVICE_CONNECTED : TACTA_DEVICE_DISCONNECTED;
  }

 private:
  ScriptSettings settings() const {
    ScriptSettings s;
    s.pattern = static_cast<Pattern>(params_.choice("pattern"));
    s.waypoints = params_.vector("waypoints");
    s.rest_position = origin_;
    s.approach_axis = to_point(params_.vector("approach_axis"), {0, 1, 0});
    s.approach_height = params_.real("approach_height");
    s.depth = params_.real("depth");
    s.tap_point = to_point(params_.vector("tap_point"), {0, 0, 0});
    s.tap_period = params_.real("tap_period");
    s.stroke_start = to_point(params_.vector("stroke_start"), {0, 0, 0});
    s.stroke_end = to_point(params_.vector("stroke_end"), {0.02, 0, 0});
    s.stroke_speed = params_.real("stroke_speed");
    s.palpation_points = params_.vector("palpation_points");
    s.travel_duration = params_.real("travel_duration");
    s.press_duration = params_.real("press_duration");
    s.dwell_duration = params_.real("dwell_duration");
    s.palpation_repeat = params_.flag("palpation_repeat");
    return s;
  }

  void integrate(double from, double to) noexcept {
    const int steps =
        std::clamp(static_cast<int>(std::ceil((to - from) / max_substep_)), 1, kMaxSubsteps);
    const double h = (to - from) / steps;
    Point previous_target = script_.target(from);
    for (int step = 1; step <= steps; ++step) {
      const Point target = script_.target(from + step * h);
      for (int i = 0; i < 3; ++i) {
        const double target_velocity = (target[i] - previous_target[i]) / h;
        const double hand =
            stiffness_ * (target[i] - position_[i]) + damping_ * (target_velocity - velocity_[i]);
        velocity_[i] += (hand + force_[i]) / mass_ * h;  // semi-implicit: velocity first
        position_[i] += velocity_[i] * h;
        if (limit_to_workspace_)
          devices::stop_at_workspace(origin_, static_cast<size_t>(i), position_, velocity_);
      }
      previous_target = target;
    }
  }

  void fill(double time, tacta_device_sample& sample) noexcept {
    sample.time = time;
    for (int i = 0; i < 3; ++i) {
      double p = position_[i];
      if (resolution_ > 0.0)
        p = origin_[i] + std::round((p - origin_[i]) / resolution_) * resolution_;
      if (noise_std_ > 0.0) p += noise_std_ * noise_.next();
      sample.position[i] = p;
      sample.velocity[i] = velocity_[i];
    }
    sample.orientation[0] = 1.0;
    sample.orientation[1] = sample.orientation[2] = sample.orientation[3] = 0.0;
    sample.buttons = button_schedule_.buttons(time);
  }

  sdk::Params params_;  // views setup's arrays: used only during construction
  Point origin_;
  HandScript script_;
  ButtonSchedule button_schedule_;
  double mass_, stiffness_, damping_, resolution_, noise_std_;
  bool limit_to_workspace_;
  GaussianNoise noise_;
  double max_substep_ = 1e-4;
  bool connected_ = false;
  bool started_ = false;
  double last_time_ = 0.0;
  Point position_{0.0, 0.0, 0.0};
  Point velocity_{0.0, 0.0, 0.0};
  Point force_{0.0, 0.0, 0.0};
};

}  // namespace tacta::sim_stylus

TACTA_PLUGIN_EXPORT(tacta::sdk::device_descriptor<tacta::sim_stylus::SimStylus>())
