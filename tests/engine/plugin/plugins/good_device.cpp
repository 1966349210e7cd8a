// Test plugin: a well-formed device written with the SDK. The tip moves along x as
// amplitude * sin(2 pi frequency t); it has no status() method, so that optional entry stays NULL.
#include <array>
#include <cmath>
#include <numbers>

#include "tacta/sdk/device.hpp"

namespace {

class SineStylus {
 public:
  static constexpr const char* kName = "test_sine_stylus";
  static constexpr const char* kDescription = "stylus tip on a sine along x (test only)";
  static constexpr uint32_t kVersion = 100;  // 0.1.0
  static constexpr std::array<tacta_param_spec, 2> kParams{
      tacta::sdk::real_param("amplitude", "m", 0.01, 0.0, 1.0, "peak displacement"),
      tacta::sdk::real_param("frequency", "Hz", 1.0, 0.0, 1000.0, "oscillation frequency"),
  };

  explicit SineStylus(const tacta_device_setup& setup) {
    const tacta::sdk::Params params(kParams, setup.params, setup.param_count);
    amplitude_ = params.real("amplitude");
    frequency_ = params.real("frequency");
  }
  void connect() { connected_ = true; }
  void disconnect() noexcept { connected_ = false; }
  tacta_device_state read(double time, tacta_device_sample& sample) noexcept {
    sample = {};
    sample.time = time;
    sample.position[0] = amplitude_ * std::sin(2 * std::numbers::pi * frequency_ * time);
    sample.orientation[0] = 1.0;
    return connected_ ? TACTA_DEVICE_CONNECTED : TACTA_DEVICE_DISCONNECTED;
  }
  void write(double, const tacta_device_command&) noexcept {}
  tacta_device_capabilities capabilities() const noexcept {
    tacta_device_capabilities c{};
    c.peak_force = 3.3;  // N
    c.nominal_rate = 1000;
    c.dof_in = 3;
    c.dof_out = 3;
    return c;
  }

 private:
  double amplitude_ = 0;  // m
  double frequency_ = 0;  // Hz
  bool connected_ = false;
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::device_descriptor<SineStylus>())
