// mouse: the viewer's mouse as an Omni-class haptic device. The host feeds a target point
// through the device API's input entry (x, y, z in m); the stylus is a point mass pulled toward
// that target by a hand impedance (spring and damper, as sim_stylus's scripted hand), and the
// force written to the device acts on the same mass, so the rendered force pushes back on the
// motion (closed loop): pressing into a body, the stylus stops near its surface like a hand
// that meets resistance. A fourth input value sets the sample's buttons (a bit mask, such as
// the viewer's cut key holding a blade's button). Capabilities are the Phantom Omni's (peak
// 3.3 N, continuous 0.88 N, about 1 N/mm usable stiffness at 1 kHz; numbers in
// docs/REFERENCES.md).
//
// Each instance keeps its own target and buttons: the host feeds them through
// Simulation::device_input, which calls input() with the instance the simulation owns. input()
// with a NULL instance is ignored.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "tacta/sdk/device.hpp"
#include "tacta_devices/omni_profile.hpp"
#include "tacta_devices/seqlock_slot.hpp"
#include "tacta_devices/state_bytes.hpp"

namespace tacta::mouse_device {
namespace {

using Point = std::array<double, 3>;

constexpr double kTeleportGap = 1.0;  // s; a longer gap (or time going back) restarts at the target
constexpr int kMaxSubsteps = 100000;
constexpr double kMaxButtons = 4294967295.0;  // 32 button bits (tacta_device_sample::buttons)

Point to_point(std::span<const double> v, Point fallback) {
  return v.size() >= 3 ? Point{v[0], v[1], v[2]} : fallback;
}

}  // namespace

class MouseDevice {
 public:
  static constexpr const char* kName = "mouse";
  static constexpr const char* kDescription =
      "The viewer's mouse as an Omni-class stylus: follows a host-fed target through a hand "
      "impedance";
  static constexpr uint32_t kVersion = 10000;
  static constexpr double kBig = 1e6;
  static constexpr std::array<tacta_param_spec, 6> kParams{{
      sdk::vector_param("start_position", "m", 3, "0 0.1 0", -kBig, kBig,
                        "target until the host feeds one"),
      sdk::vector_param("workspace_origin", "m", 3, "0 0.1 0", -kBig, kBig,
                        "centre of the reported workspace"),
      sdk::bool_param("limit_to_workspace", false, "the stylus stops at the workspace box"),
      sdk::real_param("hand_mass", "kg", 0.1, 1e-3, 10.0, "stylus plus hand effective mass"),
      sdk::real_param("hand_stiffness", "N/m", 300.0, 0.0, 1e5, "hand spring toward the target"),
      sdk::real_param("hand_damping", "N s/m", 11.0, 0.0, 1e4,
                      "hand damper on the velocity (critical for the defaults)"),
  }};

  explicit MouseDevice(const tacta_device_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    start_ = to_point(params.vector("start_position"), {0, 0.1, 0});
    origin_ = to_point(params.vector("workspace_origin"), {0, 0.1, 0});
    limit_to_workspace_ = params.flag("limit_to_workspace");
    mass_ = params.real("hand_mass");
    stiffness_ = params.real("hand_stiffness");
    damping_ = params.real("hand_damping");
    if (!(mass_ > 0.0)) throw std::invalid_argument("mouse: hand_mass must be > 0 kg");
    // Sub-step: a fifth of the hand spring's 1/omega and half its damping time, at most 0.1 ms.
    if (stiffness_ > 0.0)
      max_substep_ = std::min(max_substep_, 0.2 * std::sqrt(mass_ / stiffness_));
    if (damping_ > 0.0) max_substep_ = std::min(max_substep_, 0.5 * mass_ / damping_);
  }

  // Host thread (the viewer's), while the haptic thread may be in read(): the slot and the
  // buttons are lock-free. x, y, z (m) move the target; a fourth value, the buttons as a bit
  // mask (a whole number 0 to 2^32 - 1), replaces the sample's buttons; with three they stay.
  // A non-finite target or a mask that is not such a number is ignored.
  static void input(MouseDevice* self, const double* values, uint32_t count) noexcept {
    if (self == nullptr || values == nullptr || count < 3) return;
    const Point p{values[0], values[1], values[2]};
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) self->target_.store(p);
    if (count >= 4 && values[3] >= 0.0 && values[3] <= kMaxButtons &&
        values[3] == std::floor(values[3]))
      self->buttons_.store(static_cast<uint32_t>(values[3]), std::memory_order_release);
  }

  void connect() { connected_ = true; }
  void disconnect() noexcept { connected_ = false; }

  tacta_device_state read(double time, tacta_device_sample& sample) noexcept {
    const Point target = current_target();
    if (!started_ || !(time - last_time_ <= kTeleportGap) || time < last_time_) {
      position_ = target;  // first read, a long gap or a restarted clock: at rest on the target
      velocity_ = {0, 0, 0};
      started_ = true;
    } else if (time > last_time_) {
      integrate(target, time - last_time_);
    }
    last_time_ = time;
    sample.time = time;
    for (int i = 0; i < 3; ++i) {
      sample.position[i] = position_[i];
      sample.velocity[i] = velocity_[i];
    }
    sample.orientation[0] = 1.0;
    sample.orientation[1] = sample.orientation[2] = sample.orientation[3] = 0.0;
    sample.buttons = buttons_.load(std::memory_order_acquire);
    return connected_ ? TACTA_DEVICE_CONNECTED : TACTA_DEVICE_DISCONNECTED;
  }

  void write(double, const tacta_device_command& command) noexcept {
    force_ = devices::saturate_force(command.force);
  }

  tacta_device_capabilities capabilities() const noexcept {
    return devices::omni_capabilities(origin_, 3);
  }

  // Checkpoints: the stylus's motion and held force (the target and the buttons are the host's
  // input, fed anew).
  size_t save_state(void* bytes, size_t capacity) const noexcept {
    return devices::save_fields(bytes, capacity, started_, last_time_, position_, velocity_,
                                force_);
  }
  void load_state(const void* bytes, size_t size) {
    devices::load_fields("mouse", bytes, size, started_, last_time_, position_, velocity_, force_);
  }

 private:
  Point current_target() const noexcept {
    Point target = start_;
    target_.load(target);  // keeps start_ until the host feeds a target
    return target;
  }

  // Semi-implicit Euler of the hand-held stylus over `span` s, target held (it is a sample).
  void integrate(const Point& target, double span) noexcept {
    const int steps = std::clamp(static_cast<int>(std::ceil(span / max_substep_)), 1, kMaxSubsteps);
    const double h = span / steps;
    for (int step = 0; step < steps; ++step)
      for (int i = 0; i < 3; ++i) {
        const double hand = stiffness_ * (target[i] - position_[i]) - damping_ * velocity_[i];
        velocity_[i] += (hand + force_[i]) / mass_ * h;
        position_[i] += velocity_[i] * h;
        if (limit_to_workspace_)
          devices::stop_at_workspace(origin_, static_cast<size_t>(i), position_, velocity_);
      }
  }

  devices::SeqlockSlot<3> target_;    // host thread -> haptic thread
  std::atomic<uint32_t> buttons_{0};  // host thread -> haptic thread: bit i = button i held
  Point start_{}, origin_{};
  bool limit_to_workspace_ = false;
  double mass_ = 0.1, stiffness_ = 300, damping_ = 11;
  double max_substep_ = 1e-4;
  bool connected_ = false;
  bool started_ = false;
  double last_time_ = 0.0;
  Point position_{0, 0, 0}, velocity_{0, 0, 0}, force_{0, 0, 0};
};

}  // namespace tacta::mouse_device

TACTA_PLUGIN_EXPORT(tacta::sdk::device_descriptor<tacta::mouse_device::MouseDevice>())
