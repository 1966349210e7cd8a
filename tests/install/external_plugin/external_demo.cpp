// An out-of-tree device plugin: holds the stylus still at `rest_x` and scales commanded forces by
// `gain`. It exists to prove the installed SDK and tacta_add_plugin work outside the source tree.
#include <array>

#include "tacta/sdk/device.hpp"

namespace {

class ExternalDemo {
 public:
  static constexpr const char* kName = "external_demo";
  static constexpr const char* kDescription =
      "out-of-tree plugin built against the installed package";
  static constexpr uint32_t kVersion = 100;
  static constexpr std::array<tacta_param_spec, 2> kParams{
      tacta::sdk::real_param("gain", "", 1.0, 0.0, 10.0, "force scale"),
      tacta::sdk::real_param("rest_x", "m", 0.0, -1.0, 1.0, "stylus x position"),
  };
  explicit ExternalDemo(const tacta_device_setup& setup) {
    const tacta::sdk::Params params(kParams, setup.params, setup.param_count);
    rest_x_ = params.real("rest_x");
  }
  void connect() {}
  void disconnect() noexcept {}
  tacta_device_state read(double time, tacta_device_sample& sample) noexcept {
    sample = {};
    sample.time = time;
    sample.position[0] = rest_x_;
    sample.orientation[0] = 1.0;
    return TACTA_DEVICE_CONNECTED;
  }
  void write(double, const tacta_device_command&) noexcept {}
  tacta_device_capabilities capabilities() const noexcept { return {}; }

 private:
  double rest_x_ = 0;  // m
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::device_descriptor<ExternalDemo>())
