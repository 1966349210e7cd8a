// net: a real haptic device bridged over UDP from its vendor SDK's process (any machine), with
// the protocol of tacta_net_protocol.h and the clients tacta_net_device.h (C) and
// tacta_net_device.py. The network runs on the link's own thread (net_link.hpp); read() and
// write() only touch lock-free slots. Silence past `watchdog` makes read() report DISCONNECTED
// at once, so the engine sends zero force, and the next datagram reconnects; a BYE ends the
// device's part in the run (FINISHED: zero force, no fault).
//
// For passivity under delay the plugin also keeps the simulation side's port energies (sampled
// power f.v dt of the force written against the velocity the device reported) and sends them
// with every force: the device side bounds what it returns to the hand by them (two-port time-
// domain passivity, docs/DEVICES.md).
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <unistd.h>

#include "net_link.hpp"
#include "tacta/sdk/device.hpp"

namespace tacta::net_device {

class NetDevice {
 public:
  static constexpr const char* kName = "net";
  static constexpr const char* kDescription =
      "A real device bridged over UDP from its vendor SDK (tacta_net_device.h / .py clients)";
  static constexpr uint32_t kVersion = 10000;
  static constexpr std::array<tacta_param_spec, 7> kParams{{
      {"bind_address", TACTA_PARAM_TEXT, "text", 0, 0, 0, nullptr, "127.0.0.1", 0,
       "numeric address to listen on (0.0.0.0: every interface)"},
      sdk::int_param("port", TNET_DEFAULT_PORT, 0, 65535,
                     "UDP port (0: an ephemeral one, see port_file)"),
      sdk::text_param("port_file", "",
                      "if set, the bound port is written there (relative to the scene's folder)"),
      sdk::real_param("watchdog", "s", 0.05, 1e-3, 10.0,
                      "silence longer than this: zero force, disconnected"),
      sdk::real_param("connect_timeout", "s", 10.0, 0.0, 3600.0,
                      "how long connect waits for the device's HELLO and first STATE"),
      sdk::real_param("late_threshold", "s", 0.01, 0.0, 10.0,
                      "a STATE slower than the session's fastest by more is counted late"),
      sdk::real_param("max_force", "N", 0.0, 0.0, 1e4,
                      "caps the device's announced peak force (0: no cap)"),
  }};

  explicit NetDevice(const tacta_device_setup& setup) {
    const sdk::Params params(kParams, setup.params, setup.param_count);
    watchdog_s_ = params.real("watchdog");
    connect_timeout_s_ = params.real("connect_timeout");
    max_force_ = params.real("max_force");
    link_ = std::make_unique<NetLink>(std::string(params.text("bind_address")),
                                      static_cast<uint16_t>(params.integer("port")), watchdog_s_,
                                      params.real("late_threshold"));
    const std::string port_file(params.text("port_file"));  // a path: the engine resolved it
    if (!port_file.empty()) {
      std::ofstream(port_file + ".tmp") << link_->port() << "\n";
      std::rename((port_file + ".tmp").c_str(),
                  port_file.c_str());  // readers never see half a number
    }
    std::snprintf(reason_, sizeof reason_, "waiting for a device on UDP port %u", link_->port());
  }

  void connect() {
    tnet_hello hello{};
    const double deadline = now_seconds() + connect_timeout_s_;
    if (!link_->wait_for_hello(connect_timeout_s_, hello))
      throw std::runtime_error("net: no HELLO from a device on UDP port " +
                               std::to_string(link_->port()) + " within " +
                               std::to_string(connect_timeout_s_) + " s");
    std::array<double, StateSlot::kSize> v{};
    while (!link_->state().load(v) && now_seconds() < deadline) usleep(1000);
    if (!link_->state().load(v))
      throw std::runtime_error(
          "net: the device said HELLO but sent no STATE within the connect timeout");
    capabilities_ = to_capabilities(hello);
    connected_ = true;
  }
  void disconnect() noexcept { connected_ = false; }

  tacta_device_state read(double, tacta_device_sample& sample) noexcept {
    std::array<double, StateSlot::kSize> v{};
    const bool have = link_->state().load(v);
    const auto session = static_cast<uint32_t>(v[StateSlot::kSession]);
    const bool said_bye = v[StateSlot::kBye] != 0.0;
    const double silence = now_seconds() - v[StateSlot::kArrival];
    if (!connected_ || !have || said_bye || silence > watchdog_s_) {
      if (live_) {
        live_ = false;
        said_bye_ = said_bye;
        if (said_bye)
          std::snprintf(reason_, sizeof reason_, "the device said BYE");
        else {
          ++watchdog_trips_;
          std::snprintf(reason_, sizeof reason_,
                        "watchdog: no datagram for %.0f ms (limit %.0f ms)", silence * 1e3,
                        watchdog_s_ * 1e3);
        }
        post_force(session, {0, 0, 0},
                   TACTA_DEVICE_DISCONNECTED);  // zero at once, even before the engine's write
      }
      // A BYE ends the session on purpose (no fault): the device is done for this run.
      return said_bye ? TACTA_DEVICE_FINISHED : TACTA_DEVICE_DISCONNECTED;
    }
    if (session !=
        session_) {  // a new session: its energy budget starts from zero, as the device's does
      session_ = session;
      returned_J_ = absorbed_J_ = 0.0;
    }
    live_ = true;
    for (int a = 0; a < 3; ++a) {
      sample.position[a] = v[StateSlot::kPosition + a];
      sample.velocity[a] = v[StateSlot::kVelocity + a];
      velocity_[a] = sample.velocity[a];
    }
    for (int a = 0; a < 4; ++a) sample.orientation[a] = v[StateSlot::kOrientation + a];
    sample.buttons = static_cast<uint32_t>(v[StateSlot::kButtons]);
    sample.time = v[StateSlot::kArrival];
    return TACTA_DEVICE_CONNECTED;
  }

  void write(double time, const tacta_device_command& command) noexcept {
    const double dt = time - last_write_time_;
    last_write_time_ = time;
    const std::array<double, 3> f{command.force[0], command.force[1], command.force[2]};
    if (dt > 0.0 && dt < 0.1) {
      const double work = (f[0] * velocity_[0] + f[1] * velocity_[1] + f[2] * velocity_[2]) *
                          dt;  // J, on the device
      (work > 0.0 ? returned_J_ : absorbed_J_) += std::abs(work);
    }
    post_force(session_, f, live_ ? TACTA_DEVICE_CONNECTED : TACTA_DEVICE_DISCONNECTED);
  }

  tacta_device_capabilities capabilities() const noexcept { return capabilities_; }

  tacta_device_state status(char* reason, size_t capacity) const noexcept {
    sdk::write_message(reason, capacity, live_ ? "connected" : reason_);
    return live_       ? TACTA_DEVICE_CONNECTED
           : said_bye_ ? TACTA_DEVICE_FINISHED
                       : TACTA_DEVICE_DISCONNECTED;
  }

  uint32_t counters(tacta_device_counter* out, uint32_t capacity) const noexcept {
    const LinkCounts& c = link_->counts();
    const uint64_t dropped = c.malformed + c.duplicates + c.out_of_order + c.foreign;
    const double p50 = link_->round_trips().quantile(0.5),
                 p99 = link_->round_trips().quantile(0.99);
    const tacta_device_counter all[] = {
        {"port", static_cast<double>(link_->port())},
        {"packets_in", static_cast<double>(c.packets_in)},
        {"packets_out", static_cast<double>(c.packets_out)},
        {"dropped", static_cast<double>(dropped)},
        {"dropped_malformed", static_cast<double>(c.malformed)},
        {"dropped_duplicate", static_cast<double>(c.duplicates)},
        {"dropped_out_of_order", static_cast<double>(c.out_of_order)},
        {"dropped_foreign_session", static_cast<double>(c.foreign)},
        {"late", static_cast<double>(c.late)},
        {"watchdog_trips", static_cast<double>(watchdog_trips_)},
        {"sessions", static_cast<double>(c.sessions)},
        {"byes", static_cast<double>(c.byes)},
        {"round_trip_samples", static_cast<double>(link_->round_trips().count())},
        {"round_trip_p50_ms", p50 < 0 ? -1.0 : p50 * 1e3},
        {"round_trip_p99_ms", p99 < 0 ? -1.0 : p99 * 1e3},
        {"energy_returned_J", returned_J_},
        {"energy_absorbed_J", absorbed_J_},
    };
    const auto n = static_cast<uint32_t>(sizeof all / sizeof all[0]);
    for (uint32_t i = 0; i < n && i < capacity; ++i) out[i] = all[i];
    return n;
  }

 private:
  void post_force(uint32_t session, const std::array<double, 3>& f,
                  tacta_device_state state) noexcept {
    link_->force().store({f[0], f[1], f[2], returned_J_, absorbed_J_, static_cast<double>(state),
                          static_cast<double>(session)});
  }

  tacta_device_capabilities to_capabilities(const tnet_hello& h) const noexcept {
    tacta_device_capabilities c{};
    for (int a = 0; a < 3; ++a) {
      c.workspace_min[a] = h.workspace_min[a];
      c.workspace_max[a] = h.workspace_max[a];
    }
    c.peak_force = max_force_ > 0.0 ? std::min(h.peak_force, max_force_) : h.peak_force;
    c.continuous_force = std::min(h.continuous_force, c.peak_force);
    c.usable_stiffness = h.usable_stiffness;
    c.nominal_rate = h.nominal_rate;
    c.dof_in = h.dof_in;
    c.dof_out = h.dof_out;
    return c;
  }

  std::unique_ptr<NetLink> link_;
  double watchdog_s_ = 0.05, connect_timeout_s_ = 10.0, max_force_ = 0.0;
  tacta_device_capabilities capabilities_{};  // before connect: zero peak, the engine sends nothing
  bool connected_ = false, live_ = false, said_bye_ = false;
  uint32_t session_ = 0;
  uint64_t watchdog_trips_ = 0;
  double last_write_time_ = 0.0;
  std::array<double, 3> velocity_{};
  double returned_J_ = 0.0, absorbed_J_ = 0.0;  // J, this session's port energies (sampled power)
  char reason_[160] = {0};
};

}  // namespace tacta::net_device

TACTA_PLUGIN_EXPORT(tacta::sdk::device_descriptor<tacta::net_device::NetDevice>())
