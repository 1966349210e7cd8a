// The net device plugin through the real C ABI, with the real C client on a thread of the test:
// connect, forces back, watchdog (zero force at once, disconnected, clean reconnect), bad,
// duplicate, out-of-order and foreign datagrams dropped and counted, connect timeout.
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <thread>

#include "device_harness.hpp"
#include "tacta_net_device.h"

namespace tacta::testing {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// The device side: a client that sends a STATE every millisecond while `sending` is set.
class Bridge {
 public:
  explicit Bridge(const fs::path& port_file) {
    thread_ = std::thread([this, port_file] {
      for (int i = 0; i < 500 && !fs::exists(port_file); ++i) std::this_thread::sleep_for(10ms);
      unsigned port = 0;
      std::ifstream(port_file) >> port;
      const tnet_hello caps{{-1, -1, -1}, {1, 1, 1}, 2.5, 1.0, 800.0, 1000.0, 3, 3};
      char error[256];
      if (tacta_net_open(&dev_, "127.0.0.1", static_cast<uint16_t>(port), &caps, error,
                         sizeof error) != 0)
        return;
      opened_ = true;
      while (!stop_) {
        if (sending_) {
          const tnet_state s{{0.01, 0.02, 0.03}, {1, 0, 0, 0}, {0, 0.1, 0}, 1, 0};
          tacta_net_send_state(&dev_, &s);
        }
        tacta_net_poll(&dev_);
        double f[3];
        live_ = tacta_net_force(&dev_, f);
        force_y_ = f[1];
        std::this_thread::sleep_for(1ms);
      }
      tacta_net_close(&dev_);
    });
  }
  ~Bridge() {
    stop_ = true;
    thread_.join();
  }
  std::atomic<bool> sending_{true}, live_{false};
  std::atomic<double> force_y_{0.0};

 private:
  tacta_net_device dev_{};
  std::atomic<bool> stop_{false}, opened_{false};
  std::thread thread_;
};

struct NetDeviceTest : ::testing::Test {
  LoadedPlugin plugin{"tacta_net.so"};
  const tacta_device_api& api = plugin.api<tacta_device_api>("net");
  DeviceParams params{plugin.descriptor("net")};
  fs::path work = fs::path(TACTA_BINARY_DIR) / "test_work" /
                  ("net_device_" +
                   std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  void* device = nullptr;

  void SetUp() override {
    fs::remove_all(work);
    fs::create_directories(work);
    params.number("port", 0)
        .text("port_file", (work / "port").string())
        .number("connect_timeout", 10)
        .number("watchdog", 0.2);  // s: a loaded CI machine may stall a thread for 50 ms
  }
  void TearDown() override {
    if (device != nullptr) api.destroy(device);
  }
  std::string create_and_connect() {
    const tacta_device_setup setup = params.setup();
    char message[512] = {0};
    if (api.create(&setup, &device, message, sizeof message) != TACTA_OK)
      return std::string("create: ") + message;
    if (api.connect(device, message, sizeof message) != TACTA_OK)
      return std::string("connect: ") + message;
    return "";
  }
  std::map<std::string, double> counters() {
    tacta_device_counter c[64];
    const uint32_t n = api.counters(device, c, 64);
    std::map<std::string, double> out;
    for (uint32_t i = 0; i < n && i < 64; ++i) out[c[i].name] = c[i].value;
    return out;
  }
  // Reads until the state is `want` or a second passed.
  tacta_device_state read_until(tacta_device_state want, tacta_device_sample& s) {
    tacta_device_state state = TACTA_DEVICE_FAULT;
    for (int i = 0; i < 1000 && (state = api.read(device, 0.0, &s)) != want; ++i)
      std::this_thread::sleep_for(1ms);
    return state;
  }
  void write_force_y(double fy) {
    const tacta_device_command c{{0, fy, 0}, {0, 0, 0}};
    api.write(device, 0.001, &c);
  }
};

TEST_F(NetDeviceTest, ForcesGoBackAndSilenceZeroesThemThenReconnects) {
  Bridge bridge(work / "port");
  ASSERT_EQ(create_and_connect(), "");
  tacta_device_capabilities caps{};
  api.capabilities(device, &caps);
  EXPECT_DOUBLE_EQ(caps.peak_force, 2.5);  // announced in the HELLO
  tacta_device_sample s{};
  ASSERT_EQ(read_until(TACTA_DEVICE_CONNECTED, s), TACTA_DEVICE_CONNECTED);
  EXPECT_DOUBLE_EQ(s.position[1], 0.02);
  EXPECT_EQ(s.buttons, 1u);
  write_force_y(1.25);
  for (int i = 0; i < 1000 && bridge.force_y_ != 1.25; ++i) std::this_thread::sleep_for(1ms);
  EXPECT_EQ(bridge.force_y_, 1.25);

  bridge.sending_ = false;  // the device falls silent
  ASSERT_EQ(read_until(TACTA_DEVICE_DISCONNECTED, s), TACTA_DEVICE_DISCONNECTED);
  char reason[256];
  EXPECT_EQ(api.status(device, reason, sizeof reason), TACTA_DEVICE_DISCONNECTED);
  EXPECT_NE(std::string(reason).find("watchdog"), std::string::npos) << reason;
  EXPECT_EQ(counters()["watchdog_trips"], 1.0);

  bridge.sending_ = true;  // it comes back: zero until the simulation answers the new pose
  ASSERT_EQ(read_until(TACTA_DEVICE_CONNECTED, s), TACTA_DEVICE_CONNECTED);
  std::this_thread::sleep_for(20ms);
  EXPECT_EQ(bridge.force_y_, 0.0);
  write_force_y(0.5);
  for (int i = 0; i < 1000 && bridge.force_y_ != 0.5; ++i) std::this_thread::sleep_for(1ms);
  EXPECT_EQ(bridge.force_y_, 0.5);
  const auto c = counters();
  EXPECT_EQ(c.at("watchdog_trips"), 1.0);
  EXPECT_GT(c.at("round_trip_samples"), 0.0);
  EXPECT_GT(c.at("round_trip_p50_ms"), 0.0);
  EXPECT_EQ(c.at("sessions"), 1.0);
}

TEST_F(NetDeviceTest, BadDuplicateOutOfOrderAndForeignDatagramsAreDroppedAndCounted) {
  Bridge bridge(work / "port");
  ASSERT_EQ(create_and_connect(), "");
  unsigned port = 0;
  std::ifstream(work / "port") >> port;
  const int raw = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const auto send = [&](const std::vector<unsigned char>& d) {
    sendto(raw, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to), sizeof to);
  };
  send({1, 2, 3});                             // short
  send(std::vector<unsigned char>(40, 0xAB));  // no magic
  const tnet_state s{{0, 0, 0}, {1, 0, 0, 0}, {0, 0, 0}, 0, 0};
  std::vector<unsigned char> foreign(TNET_HEADER_SIZE + TNET_STATE_SIZE);
  tnet_header h{};
  h.type = TNET_STATE;
  h.session = 77;  // another device while the bridge is live
  h.sequence = 1;
  tnet_encode_header(foreign.data(), h);
  tnet_encode_state(foreign.data() + TNET_HEADER_SIZE, &s);
  send(foreign);
  std::this_thread::sleep_for(50ms);
  auto c = counters();
  EXPECT_EQ(c["dropped_malformed"], 2.0);
  EXPECT_EQ(c["dropped_foreign_session"], 1.0);

  // Replays of the bridge's own datagrams: the link saw newer ones already.
  tacta_device_sample sample{};
  ASSERT_EQ(read_until(TACTA_DEVICE_CONNECTED, sample), TACTA_DEVICE_CONNECTED);
  bridge.sending_ = false;
  std::this_thread::sleep_for(
      400ms);  // the bridge's session is silent now: a new one may take over
  h.session = 78;
  for (uint32_t seq : {5u, 5u, 3u, 6u}) {  // 5 taken, 5 duplicate, 3 out of order, 6 taken
    h.sequence = seq;
    tnet_encode_header(foreign.data(), h);
    send(foreign);
  }
  std::this_thread::sleep_for(50ms);
  c = counters();
  EXPECT_EQ(c["dropped_duplicate"], 1.0);
  EXPECT_EQ(c["dropped_out_of_order"], 1.0);
  EXPECT_EQ(c["sessions"], 2.0);
  EXPECT_EQ(c["dropped"], 5.0);
  close(raw);
}

TEST_F(NetDeviceTest, NoDeviceMeansAConnectErrorNamingThePort) {
  params.number("connect_timeout", 0.2);
  const std::string error = create_and_connect();
  EXPECT_NE(error.find("connect: net: no HELLO from a device on UDP port"), std::string::npos)
      << error;
}

TEST_F(NetDeviceTest, BindAddressThatIsNotAnAddressIsRefusedAtCreate) {
  params.text("bind_address", "not-an-address");
  const std::string error = create_and_connect();
  EXPECT_NE(error.find("create: net: bind_address 'not-an-address'"), std::string::npos) << error;
}

}  // namespace
}  // namespace tacta::testing
