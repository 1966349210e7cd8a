// replay through the real C ABI: exact at samples, linear between, slerp for orientation, a
// sim_stylus session recorded then replayed bit for bit, the end of the log, bad logs at create.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <numbers>
#include <unistd.h>

#include "device_harness.hpp"
#include "tacta/device_log.hpp"

namespace tacta::testing {
namespace {

std::string temp_dir() {
  const auto dir =
      std::filesystem::temp_directory_path() / ("tacta_replay_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir.string();
}

struct ReplayTest : ::testing::Test {
  LoadedPlugin plugin{"tacta_replay.so"};
  const tacta_device_api& api = plugin.api<tacta_device_api>("replay");
  DeviceParams params{plugin.descriptor("replay")};
  std::string dir = temp_dir();
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::string write_log(const std::string& name, const std::vector<DeviceLogSample>& samples) {
    write_device_log(dir + "/" + name, samples.data(), samples.size());
    return name;
  }
  void write_text(const std::string& name, const std::string& text) {
    std::ofstream(dir + "/" + name) << text;
  }
};

std::vector<DeviceLogSample> three_samples() {
  std::vector<DeviceLogSample> s(3);
  for (int i = 0; i < 3; ++i) {
    s[i].time = 0.01 * i;
    s[i].position[0] = 0.001 * i * i + 0.1;
    s[i].position[1] = -0.003 * i;
    s[i].velocity[2] = 0.5 * i;
    s[i].buttons = static_cast<uint32_t>(i);
  }
  s[1].orientation[0] = std::sqrt(0.5);  // 90 degrees about z
  s[1].orientation[3] = std::sqrt(0.5);
  return s;
}

TEST_F(ReplayTest, ExactAtSamplesAndLinearBetween) {
  const auto samples = three_samples();
  params.text("log", write_log("three.csv", samples));
  DeviceInstance device(api, params.setup(1, dir));
  ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
  for (const DeviceLogSample& expected : samples) {
    tacta_device_sample s{};
    EXPECT_EQ(device.read(expected.time, s), TACTA_DEVICE_CONNECTED);
    EXPECT_EQ(std::memcmp(s.position, expected.position, sizeof s.position), 0);
    EXPECT_EQ(std::memcmp(s.velocity, expected.velocity, sizeof s.velocity), 0);
    EXPECT_EQ(std::memcmp(s.orientation, expected.orientation, sizeof s.orientation), 0);
    EXPECT_EQ(s.buttons, expected.buttons);
  }
  for (double u : {0.25, 0.5, 0.9}) {
    const tacta_device_sample s = device.read(0.01 + 0.01 * u);
    EXPECT_NEAR(s.position[0],
                samples[1].position[0] + u * (samples[2].position[0] - samples[1].position[0]),
                1e-15);
    EXPECT_NEAR(s.position[1],
                samples[1].position[1] + u * (samples[2].position[1] - samples[1].position[1]),
                1e-15);
    EXPECT_NEAR(s.velocity[2], 0.5 + 0.5 * u, 1e-14);
    EXPECT_EQ(s.buttons, 1u);  // from the earlier sample
    // slerp from 90 degrees about z back to identity: (1 - u) * 90 degrees.
    const double half_angle = 0.5 * (1.0 - u) * std::numbers::pi / 2.0;
    EXPECT_NEAR(s.orientation[0], std::cos(half_angle), 1e-12);
    EXPECT_NEAR(s.orientation[3], std::sin(half_angle), 1e-12);
  }
}

TEST_F(ReplayTest, PastTheEndReportsFinishedWithAReasonUnlessLooping) {
  params.text("log", write_log("three.csv", three_samples())).number("time_offset", 1.0);
  DeviceInstance device(api, params.setup(1, dir));
  ASSERT_EQ(device.create_status(), TACTA_OK) << device.message();
  tacta_device_sample s{};
  EXPECT_EQ(device.read(1.01, s), TACTA_DEVICE_CONNECTED);
  EXPECT_DOUBLE_EQ(s.position[0], 0.101);  // offset: log time 0.01 plays at 1.01 s
  EXPECT_EQ(device.read(1.02, s), TACTA_DEVICE_CONNECTED);
  EXPECT_EQ(device.read(1.021, s), TACTA_DEVICE_FINISHED);
  std::string reason;
  EXPECT_EQ(device.status(reason), TACTA_DEVICE_FINISHED);
  EXPECT_NE(reason.find("ended"), std::string::npos) << reason;

  params.number("loop", 1.0);
  DeviceInstance looping(api, params.setup(1, dir));
  EXPECT_EQ(looping.read(1.03, s), TACTA_DEVICE_CONNECTED);  // 1.03 s -> log time 0.01 again
  EXPECT_NEAR(s.position[0], 0.101, 1e-12);
}

// A sim_stylus session with noise (so positions are arbitrary doubles) is recorded, written and
// replayed at the same ticks: every replayed sample equals the recorded one, bit for bit.
TEST_F(ReplayTest, RecordedSessionReplaysBitForBit) {
  LoadedPlugin stylus_plugin("tacta_sim_stylus.so");
  DeviceParams stylus_params(stylus_plugin.descriptor("sim_stylus"));
  stylus_params.number("pattern", 1).number("noise_std", 2e-5).vector("tap_point", {0.0, 0.0, 0.0});
  DeviceInstance stylus(stylus_plugin.api<tacta_device_api>("sim_stylus"), stylus_params.setup(7));
  ASSERT_EQ(stylus.create_status(), TACTA_OK) << stylus.message();
  DeviceLogRecorder recorder(2000);
  for (int n = 0; n < 1500; ++n) {
    const double t = n * 1e-3;
    const tacta_device_sample s = stylus.read(t);
    const double force_y = s.position[1] < 0.0 ? -800.0 * s.position[1] : 0.0;
    stylus.write(t, 0.0, force_y, 0.0);
    DeviceLogSample logged;
    logged.time = s.time;
    std::memcpy(logged.position, s.position, sizeof s.position);
    std::memcpy(logged.orientation, s.orientation, sizeof s.orientation);
    std::memcpy(logged.velocity, s.velocity, sizeof s.velocity);
    logged.buttons = s.buttons;
    logged.force[1] = force_y;
    recorder.record(logged);
  }
  recorder.write_csv(dir + "/session.csv");
  params.text("log", "session.csv");
  DeviceInstance replay(api, params.setup(1, dir));
  ASSERT_EQ(replay.create_status(), TACTA_OK) << replay.message();
  int mismatches = 0;
  for (size_t i = 0; i < recorder.size(); ++i) {
    const DeviceLogSample& expected = recorder.at(i);
    const tacta_device_sample s = replay.read(expected.time);
    mismatches += std::memcmp(s.position, expected.position, sizeof s.position) != 0 ||
                  std::memcmp(s.velocity, expected.velocity, sizeof s.velocity) != 0 ||
                  std::memcmp(s.orientation, expected.orientation, sizeof s.orientation) != 0 ||
                  s.time != expected.time;
  }
  EXPECT_EQ(mismatches, 0);
}

TEST_F(ReplayTest, TruncatedOrMalformedLogIsRefusedAtCreateWithTheLine) {
  const std::string header = std::string(kDeviceLogHeader) + "\n";
  const std::string good = "0,0,0,0,1,0,0,0,0,0,0,0,0,0,0\n";
  struct Case {
    std::string text, expected;
  };
  const std::vector<Case> cases = {
      {header + good + good + "0.002,0.1,0.2,0.3,1,0", "bad.csv:4: expected 15 columns, found 6"},
      {header + good + "0.001,0.1,x,0.3,1,0,0,0,0,0,0,0,0,0,0\n",
       "bad.csv:3: expected a finite number in column 3 (py)"},
      {header, "bad.csv:2: expected at least one sample"},
      {"", "bad.csv:1: expected the device log header"},
  };
  for (const Case& c : cases) {
    write_text("bad.csv", c.text);
    params.text("log", "bad.csv");
    DeviceInstance device(api, params.setup(1, dir));
    EXPECT_EQ(device.create_status(), TACTA_ERR_INVALID_ARGUMENT);
    EXPECT_NE(device.message().find(c.expected), std::string::npos) << device.message();
  }
  // Outside the recorded device's workspace: the samples span 0.3 m in x, an Omni 0.16 m.
  write_text("wide.csv", header + good + "0.001,0.3,0,0,1,0,0,0,0,0,0,0,0,0,0\n");
  params.text("log", "wide.csv");
  DeviceInstance wide(api, params.setup(1, dir));
  EXPECT_EQ(wide.create_status(), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(wide.message().find("wide.csv:3: px = 0.3 m is outside the device's workspace"),
            std::string::npos)
      << wide.message();
  // With the workspace placed, a sample off it by more than the tolerance is refused ...
  write_text("off.csv", header + good + "0.001,0,0.075,0,1,0,0,0,0,0,0,0,0,0,0\n");
  params.text("log", "off.csv");
  params.vector("workspace_origin", {0, 0, 0});
  DeviceInstance off(api, params.setup(1, dir));
  EXPECT_EQ(off.create_status(), TACTA_ERR_INVALID_ARGUMENT);
  EXPECT_NE(off.message().find("off.csv:3: py = 0.075 m"), std::string::npos) << off.message();
  // ... and one within it is played.
  params.number("workspace_tolerance", 0.02);
  DeviceInstance within(api, params.setup(1, dir));
  EXPECT_EQ(within.create_status(), TACTA_OK) << within.message();
  params.text("log", "missing.csv");
  DeviceInstance missing(api, params.setup(1, dir));
  EXPECT_NE(missing.create_status(), TACTA_OK);
  EXPECT_NE(missing.message().find("missing.csv"), std::string::npos) << missing.message();
}

}  // namespace
}  // namespace tacta::testing
