// openigtlink: a tracker, a robot or 3D Slicer as the haptic device, over OpenIGTLink (Debian's
// libopenigtlink). Poses come in as TRANSFORM, POSITION or QTDATA; the rendered force goes back
// as a SENSOR message (3 values, N); the touched body's deformed surface goes out as POLYDATA at
// `surface_rate` so Slicer shows it live. Network I/O runs on the link's thread (igtl_link.hpp);
// read() and write() only touch lock-free slots, surface() (render thread) a triple buffer.
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "igtl_link.hpp"
#include "tacta/sdk/device.hpp"

namespace tacta::igtl_device {

class OpenIgtlinkDevice {
 public:
  static constexpr const char* kName = "openigtlink";
  static constexpr const char* kDescription =
      "3D Slicer, a tracker or a robot over OpenIGTLink: pose in, force (SENSOR) and surface "
      "(POLYDATA) out";
  static constexpr uint32_t kVersion = 10000;
  static constexpr double kBig = 1e6;
  static constexpr std::array<tacta_param_spec, 10> kParams{{
      sdk::choice_param("role", "server|client", 0,
                        "server: wait for a peer (Slicer's default); client: connect to one"),
      {"host", TACTA_PARAM_TEXT, "text", 0, 0, 0, nullptr, "127.0.0.1", 0,
       "client role: the server's address"},
      sdk::int_param("port", 18944, 0, 65535,
                     "TCP port (server role: 0 picks a free one, see port_file)"),
      sdk::text_param("port_file", "", "if set, the server's port is written there"),
      sdk::real_param("units", "m", 1e-3, 1e-9, 1e3,
                      "metres per OpenIGTLink length unit (Slicer: mm)"),
      sdk::real_param("surface_rate", "Hz", 60.0, 0.0, 1000.0,
                      "POLYDATA messages per second (0: none)"),
      sdk::real_param("connect_timeout", "s", 60.0, 0.0, 3600.0,
                      "how long connect waits for a peer and its first pose"),
      sdk::real_param(
          "watchdog", "s", 0.0, 0.0, 60.0,
          "no pose for this long: zero force, disconnected (0: only a lost connection)"),
      sdk::real_param("peak_force", "N", 3.3, 0.0, 1e4,
                      "force limit the engine keeps to (an Omni's by default)"),
      sdk::vector_param("workspace_half", "m", 3, "0.5 0.5 0.5", 0.0, kBig,
                        "half extents of the tracked workspace"),
  }};

  explicit OpenIgtlinkDevice(const tacta_device_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    LinkSettings s;
    s.server = params.choice("role") == 0;
    s.host = std::string(params.text("host"));
    s.port = params.integer("port");
    s.metres_per_unit = params.real("units");
    s.surface_rate_hz = params.real("surface_rate");
    connect_timeout_s_ = params.real("connect_timeout");
    watchdog_s_ = params.real("watchdog");
    peak_force_ = params.real("peak_force");
    const auto half = params.vector("workspace_half");
    for (size_t a = 0; a < 3 && a < half.size(); ++a) half_[a] = half[a];
    link_ = std::make_unique<IgtlLink>(s);
    const std::string port_file(params.text("port_file"));  // a path: the engine resolved it
    if (!port_file.empty()) {
      std::FILE* f = std::fopen((port_file + ".tmp").c_str(), "w");
      if (f == nullptr)
        throw std::invalid_argument("openigtlink: cannot write port_file " + port_file);
      std::fprintf(f, "%d\n", link_->port());
      std::fclose(f);
      std::rename((port_file + ".tmp").c_str(), port_file.c_str());
    }
    std::snprintf(reason_, sizeof reason_, "no OpenIGTLink peer yet (port %d)", link_->port());
  }

  void connect() {
    if (!link_->wait_for_pose(connect_timeout_s_))
      throw std::runtime_error(
          "openigtlink: no peer sent a pose (TRANSFORM, POSITION or QTDATA) on port " +
          std::to_string(link_->port()) + " within " + std::to_string(connect_timeout_s_) + " s");
    connected_ = true;
  }
  void disconnect() noexcept { connected_ = false; }

  tacta_device_state read(double, tacta_device_sample& sample) noexcept {
    std::array<double, PoseSlot::kSize> p{};
    const bool have = link_->pose().load(p);
    const double silence = now_seconds() - p[PoseSlot::kArrival];
    const bool lost = !have || p[PoseSlot::kLive] == 0.0;
    if (!connected_ || lost || (watchdog_s_ > 0 && silence > watchdog_s_)) {
      if (live_) {
        live_ = false;
        ++trips_;
        link_->force().store(
            {0, 0, 0});  // the next SENSOR says zero even before the engine's write
        if (lost)
          std::snprintf(reason_, sizeof reason_, "the OpenIGTLink peer disconnected");
        else
          std::snprintf(reason_, sizeof reason_, "watchdog: no pose for %.0f ms", silence * 1e3);
      }
      return TACTA_DEVICE_DISCONNECTED;
    }
    live_ = true;
    for (int a = 0; a < 3; ++a) {
      sample.position[a] = p[PoseSlot::kPosition + a];
      sample.velocity[a] = p[PoseSlot::kVelocity + a];
    }
    for (int a = 0; a < 4; ++a) sample.orientation[a] = p[PoseSlot::kOrientation + a];
    sample.buttons = 0;
    if (!origin_set_) {  // the workspace is centred where the tool first was
      for (int a = 0; a < 3; ++a) origin_[a] = sample.position[a];
      origin_set_ = true;
    }
    return TACTA_DEVICE_CONNECTED;
  }

  void write(double, const tacta_device_command& command) noexcept {
    link_->force().store({command.force[0], command.force[1], command.force[2]});
  }

  void surface(const tacta_device_surface& s) noexcept {
    try {
      link_->surfaces().offer(s);  // allocates at its first call only
    } catch (...) {
      surface_failed_ = true;  // out of memory: no surface stream, the device goes on
    }
  }

  tacta_device_capabilities capabilities() const noexcept {
    tacta_device_capabilities c{};
    for (int a = 0; a < 3; ++a) {
      c.workspace_min[a] = origin_[a] - half_[a];
      c.workspace_max[a] = origin_[a] + half_[a];
    }
    c.peak_force = peak_force_;
    c.continuous_force = peak_force_;
    c.usable_stiffness = 1000.0;  // N/m: what the coupling may assume of an unknown device
    c.nominal_rate = 60.0;        // Hz: a typical tracker or Slicer update rate
    c.dof_in = 6;
    c.dof_out = 3;
    return c;
  }

  tacta_device_state status(char* reason, size_t capacity) const noexcept {
    sdk::write_message(reason, capacity, live_ ? "connected" : reason_);
    return live_ ? TACTA_DEVICE_CONNECTED : TACTA_DEVICE_DISCONNECTED;
  }

  uint32_t counters(tacta_device_counter* out, uint32_t capacity) const noexcept {
    const LinkCounts& c = link_->counts();
    const tacta_device_counter all[] = {
        {"port", static_cast<double>(link_->port())},
        {"packets_in", static_cast<double>(c.messages_in)},
        {"packets_out", static_cast<double>(c.messages_out)},
        {"poses", static_cast<double>(c.poses)},
        {"surfaces_out", static_cast<double>(c.surfaces_out)},
        {"dropped", static_cast<double>(c.dropped)},
        {"ignored", static_cast<double>(c.ignored)},
        {"late", 0.0},  // TCP delivers in order: nothing arrives late, it arrives delayed
        {"watchdog_trips", static_cast<double>(trips_)},
        {"connections", static_cast<double>(c.connections)},
        {"disconnections", static_cast<double>(c.disconnections)},
        {"round_trip_p50_ms", -1.0},  // OpenIGTLink has no echo to time a round trip by
        {"round_trip_p99_ms", -1.0},
        {"surface_failed", surface_failed_ ? 1.0 : 0.0},
    };
    const auto n = static_cast<uint32_t>(sizeof all / sizeof all[0]);
    for (uint32_t i = 0; i < n && i < capacity; ++i) out[i] = all[i];
    return n;
  }

 private:
  std::unique_ptr<IgtlLink> link_;
  double connect_timeout_s_ = 60, watchdog_s_ = 0, peak_force_ = 3.3;
  std::array<double, 3> half_{0.5, 0.5, 0.5}, origin_{0, 0, 0};
  bool origin_set_ = false, connected_ = false, live_ = false, surface_failed_ = false;
  uint64_t trips_ = 0;
  char reason_[160] = {0};
};

}  // namespace tacta::igtl_device

TACTA_PLUGIN_EXPORT(tacta::sdk::device_descriptor<tacta::igtl_device::OpenIgtlinkDevice>())
