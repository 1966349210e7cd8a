// replay: plays a device session log (tacta/device_log.hpp) at its timestamps, interpolated to
// the tick. A log's sample at time_s plays at engine time time_s + time_offset. Past the end the
// device reports FINISHED (zero force from the engine) with the reason, unless `loop` is set.
// A truncated or malformed log is refused at create with file:line and what was expected.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "interpolation.hpp"
#include "tacta/sdk/device.hpp"
#include "tacta_devices/omni_profile.hpp"
#include "tacta_devices/state_bytes.hpp"

namespace tacta::replay {

class ReplayDevice {
 public:
  // s: engine time minus offset may miss the last timestamp by rounding; this is not the end yet.
  static constexpr double kEndTolerance = 1e-9;
  static constexpr const char* kName = "replay";
  static constexpr const char* kDescription = "Plays a recorded device log (CSV) at its timestamps";
  static constexpr uint32_t kVersion = 10000;
  static constexpr double kBig = 1e3;  // m: the log reader refuses positions beyond this anyway
  static constexpr std::array<tacta_param_spec, 6> kParams{{
      sdk::text_param("log", "", "device log (CSV) to play; relative to the scene's folder"),
      sdk::real_param("time_offset", "s", 0.0, -1e6, 1e6, "engine time = log time + time_offset"),
      sdk::bool_param("loop", false, "start again from the first sample after the last"),
      sdk::vector_param("workspace_size", "m", 3, "0.16 0.12 0.07", 1e-3, kBig,
                        "x y z extent of the recorded device's workspace (Omni class)"),
      sdk::vector_param("workspace_origin", "m", 3, "", -kBig, kBig,
                        "centre of that workspace in the world; none: wherever the samples are"),
      sdk::real_param("workspace_tolerance", "m", 0.01, 0.0, kBig,
                      "how far a sample may lie outside the workspace"),
  }};

  explicit ReplayDevice(const tacta_device_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    const std::string name(params.text("log"));
    if (name.empty())
      throw std::invalid_argument("replay: parameter 'log' expects a log file path, found nothing");
    std::filesystem::path path(name);
    if (path.is_relative() && setup.base_directory != nullptr && setup.base_directory[0] != '\0')
      path = std::filesystem::path(setup.base_directory) / path;
    path_ = path.string();
    try {
      samples_ = read_device_log(path_);
    } catch (const InputError& e) {
      throw std::invalid_argument(std::string("replay: ") + e.what());
    }
    if (samples_.empty())
      throw std::invalid_argument("replay: " + path_ +
                                  ":2: expected at least one sample after the header");
    check_workspace(params);
    offset_ = params.real("time_offset");
    loop_ = params.flag("loop");
    capabilities_ = compute_capabilities();
  }

  void connect() { connected_ = true; }
  void disconnect() noexcept { connected_ = false; }

  tacta_device_state read(double time, tacta_device_sample& sample) noexcept {
    double log_time = time - offset_;
    const double first = samples_.front().time;
    const double last = samples_.back().time;
    if (loop_ && log_time > last && last > first)
      log_time = first + std::fmod(log_time - first, last - first);
    const DeviceLogSample s = sample_at(samples_, log_time);
    sample.time = time;
    for (int i = 0; i < 3; ++i) {
      sample.position[i] = s.position[i];
      sample.velocity[i] = s.velocity[i];
    }
    for (int i = 0; i < 4; ++i) sample.orientation[i] = s.orientation[i];
    sample.buttons = s.buttons;
    if (!connected_) return TACTA_DEVICE_DISCONNECTED;
    if (log_time > last + kEndTolerance) {
      if (!finished_)
        std::snprintf(reason_, sizeof reason_, "log %s ended at t=%.6g s", path_.c_str(),
                      last + offset_);
      finished_ = true;
      return TACTA_DEVICE_FINISHED;
    }
    return TACTA_DEVICE_CONNECTED;
  }

  // Checkpoints: read() is a function of time; what carries is whether the log ended.
  size_t save_state(void* bytes, size_t capacity) const noexcept {
    return devices::save_fields(bytes, capacity, finished_, last_force_);
  }
  void load_state(const void* bytes, size_t size) {
    devices::load_fields("replay", bytes, size, finished_, last_force_);
  }

  void write(double, const tacta_device_command& command) noexcept {
    for (int i = 0; i < 3; ++i) last_force_[i] = command.force[i];  // a replay renders nothing
  }

  tacta_device_capabilities capabilities() const noexcept { return capabilities_; }

  tacta_device_state status(char* reason, size_t capacity) const noexcept {
    if (!connected_) {
      sdk::write_message(reason, capacity, "not connected");
      return TACTA_DEVICE_DISCONNECTED;
    }
    if (finished_) {
      sdk::write_message(reason, capacity, reason_);
      return TACTA_DEVICE_FINISHED;
    }
    sdk::write_message(reason, capacity, "playing");
    return TACTA_DEVICE_CONNECTED;
  }

 private:
  // A sample outside the workspace of the device that recorded it is a corrupt log, not a motion:
  // refused with its line (sample i is on line i + 2: the header is line 1 and the reader allows
  // no blank line between samples). Without an origin, the samples' span must fit the workspace.
  void check_workspace(const sdk::Params& params) const {
    const std::span<const double> size = params.vector("workspace_size");
    const std::span<const double> origin = params.vector("workspace_origin");
    const double tolerance = params.real("workspace_tolerance");
    double low[3], high[3];
    for (int i = 0; i < 3; ++i) low[i] = high[i] = samples_.front().position[i];
    for (size_t n = 0; n < samples_.size(); ++n) {
      for (int i = 0; i < 3; ++i) {
        const double p = samples_[n].position[i];
        const double half = 0.5 * size[static_cast<size_t>(i)];
        low[i] = std::min(low[i], p);
        high[i] = std::max(high[i], p);
        const bool outside = origin.size() == 3
                                 ? std::abs(p - origin[static_cast<size_t>(i)]) > half + tolerance
                                 : high[i] - low[i] > 2 * half + 2 * tolerance;
        if (!outside) continue;
        static constexpr const char* kColumn[3] = {"px", "py", "pz"};
        char message[512];
        std::snprintf(
            message, sizeof message,
            "replay: %s:%zu: %s = %.9g m is outside the device's workspace (%.9g m along it, %s, "
            "tolerance %.9g m; see workspace_size, workspace_origin, workspace_tolerance)",
            path_.c_str(), n + 2, kColumn[i], p, size[static_cast<size_t>(i)],
            origin.size() == 3 ? "centred on workspace_origin" : "placed where the samples are",
            tolerance);
        throw std::invalid_argument(message);
      }
    }
  }

  tacta_device_capabilities compute_capabilities() const {
    // A replay has no hardware: it reports the box its samples span and the Omni-class force
    // numbers (peak 3.3 N, docs/REFERENCES.md) so the engine limits forces the same way.
    tacta_device_capabilities c{};
    for (int i = 0; i < 3; ++i) {
      c.workspace_min[i] = c.workspace_max[i] = samples_.front().position[i];
      for (const DeviceLogSample& s : samples_) {
        c.workspace_min[i] = std::min(c.workspace_min[i], s.position[i]);
        c.workspace_max[i] = std::max(c.workspace_max[i], s.position[i]);
      }
    }
    c.peak_force = devices::kOmniPeakForce;
    c.continuous_force = devices::kOmniContinuousForce;
    c.usable_stiffness = devices::kOmniUsableStiffness;
    c.nominal_rate = 1000.0;
    c.dof_in = 6;
    c.dof_out = 3;
    return c;
  }

  std::string path_;
  std::vector<DeviceLogSample> samples_;
  double offset_ = 0.0;
  bool loop_ = false;
  bool connected_ = false;
  bool finished_ = false;
  char reason_[512] = {0};
  double last_force_[3] = {0.0, 0.0, 0.0};
  tacta_device_capabilities capabilities_{};
};

}  // namespace tacta::replay

TACTA_PLUGIN_EXPORT(tacta::sdk::device_descriptor<tacta::replay::ReplayDevice>())
