// Test plugin: a device held still 5 cm above the origin that reports a fault of its own
// (TACTA_DEVICE_FAULT) from `fault_time` s on, so a test can see a device's returned state reach
// the tick's status, Simulation::step()'s result and report.json.
#include <array>
#include <cstdio>

#include "tacta/sdk/device.hpp"

namespace {

class FaultyDevice {
 public:
  static constexpr const char* kName = "test_faulty_device";
  static constexpr const char* kDescription =
      "a still device that faults at a chosen time (test only)";
  static constexpr uint32_t kVersion = 10000;
  static constexpr std::array<tacta_param_spec, 1> kParams{
      tacta::sdk::real_param("fault_time", "s", 0.05, 0.0, 1e6, "when the device faults"),
  };
  explicit FaultyDevice(const tacta_device_setup& setup) {
    const tacta::sdk::Params params(kParams, setup.params, setup.param_count);
    fault_time_ = params.real("fault_time");
  }
  void connect() {}
  void disconnect() noexcept {}
  tacta_device_state read(double time, tacta_device_sample& sample) noexcept {
    sample.time = time;
    sample.position[0] = 0.0;
    sample.position[1] = 0.05;
    sample.position[2] = 0.0;
    return time >= fault_time_ ? TACTA_DEVICE_FAULT : TACTA_DEVICE_CONNECTED;
  }
  void write(double, const tacta_device_command&) noexcept {}
  tacta_device_capabilities capabilities() const noexcept {
    tacta_device_capabilities c{};
    for (int a = 0; a < 3; ++a) {
      c.workspace_min[a] = -1.0;
      c.workspace_max[a] = 1.0;
    }
    c.peak_force = 5.0;
    c.continuous_force = 2.0;
    c.usable_stiffness = 1000.0;
    c.nominal_rate = 1000.0;
    c.dof_in = c.dof_out = 3;
    return c;
  }
  tacta_device_state status(char* reason, size_t capacity) const noexcept {
    std::snprintf(reason, capacity, "faulted on purpose at %g s", fault_time_);
    return TACTA_DEVICE_FAULT;
  }

 private:
  double fault_time_ = 0.05;
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::device_descriptor<FaultyDevice>())
