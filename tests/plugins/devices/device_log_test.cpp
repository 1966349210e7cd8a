// The device log format (tacta/device_log.hpp): round trip, validation with file:line, recorder.
#include "tacta/device_log.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <gtest/gtest.h>

namespace tacta {
namespace {

DeviceLogSample awkward_sample(int i) {
  DeviceLogSample s;
  s.time = i * 1e-3 + 1.0 / 3.0;
  for (int k = 0; k < 3; ++k) {
    s.position[k] = std::sin(0.1 * i + k) * 0.0123456789012345678;
    s.velocity[k] = std::nextafter(1.0 / (7.0 + i + k), 1.0);
    s.force[k] = -std::cos(i + k) * 3.3;
  }
  s.orientation[0] = std::cos(0.01 * i);
  s.orientation[3] = std::sin(0.01 * i);
  s.buttons = static_cast<uint32_t>(i % 4);
  return s;
}

TEST(DeviceLog, WriteThenReadIsBitExact) {
  std::vector<DeviceLogSample> samples;
  for (int i = 0; i < 200; ++i) samples.push_back(awkward_sample(i));
  samples.back().position[0] = 5e-324;  // a denormal survives too
  const std::string path =
      (std::filesystem::temp_directory_path() / "tacta_device_log_roundtrip.csv").string();
  write_device_log(path, samples.data(), samples.size());
  const std::vector<DeviceLogSample> back = read_device_log(path);
  ASSERT_EQ(back.size(), samples.size());
  for (size_t i = 0; i < samples.size(); ++i)
    EXPECT_EQ(std::memcmp(&back[i], &samples[i], sizeof(DeviceLogSample)), 0) << "sample " << i;
  std::remove(path.c_str());
}

std::string error_of(const std::string& text) {
  try {
    parse_device_log(text, "session.csv");
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(DeviceLog, MalformedLinesNameFileLineAndWhatWasExpected) {
  const std::string header = std::string(kDeviceLogHeader) + "\n";
  const std::string good = "0,0,0,0,1,0,0,0,0,0,0,0,0,0,0\n";
  EXPECT_NE(error_of("").find("session.csv:1: expected the device log header"), std::string::npos);
  EXPECT_NE(error_of("time,x\n" + good).find("session.csv:1: expected the device log header"),
            std::string::npos);
  // Truncated: the last line stops after a few columns.
  EXPECT_NE(
      error_of(header + good + "0.001,0.1,0.2").find("session.csv:3: expected 15 columns, found 3"),
      std::string::npos)
      << error_of(header + good + "0.001,0.1,0.2");
  EXPECT_NE(error_of(header + good + good + "0.001,abc,0,0,1,0,0,0,0,0,0,0,0,0,0\n")
                .find("session.csv:4: expected a finite number in column 2 (px), found 'abc'"),
            std::string::npos);
  EXPECT_NE(error_of(header + "0,nan,0,0,1,0,0,0,0,0,0,0,0,0,0\n")
                .find("session.csv:2: expected a finite number"),
            std::string::npos);
  EXPECT_NE(error_of(header + "0,0,0,0,1,0,0,0,0,0,0,-1,0,0,0\n")
                .find("session.csv:2: expected an unsigned 32-bit integer"),
            std::string::npos);
  EXPECT_NE(error_of(header + "1,0,0,0,1,0,0,0,0,0,0,0,0,0,0\n" + good)
                .find("session.csv:3: expected non-decreasing time_s"),
            std::string::npos);
  EXPECT_NE(error_of(header + good + "\n" + good)
                .find("session.csv:3: expected a sample, found an empty line"),
            std::string::npos);
  EXPECT_NE(error_of(header + "0,0,0,0,1,0,0,0,0,0,0,0,0,0,0,7\n").find("found more"),
            std::string::npos);
  EXPECT_EQ(error_of(header + good + "\r\n"),
            "no error");  // CRLF and a trailing blank line are fine
}

TEST(DeviceLog, ImplausibleValuesAreRefusedWithTheLine) {
  const std::string header = std::string(kDeviceLogHeader) + "\n";
  const std::string good = "0,0,0,0,1,0,0,0,0,0,0,0,0,0,0\n";
  // The sample that once replayed as 1.3e29 J of injected energy.
  EXPECT_NE(error_of(header + good + "0.001,1e30,0,0,1,0,0,0,0,0,0,0,0,0,0\n")
                .find("session.csv:3: column 2 (px) = 1e+30 is beyond 1000 m"),
            std::string::npos)
      << error_of(header + good + "0.001,1e30,0,0,1,0,0,0,0,0,0,0,0,0,0\n");
  EXPECT_NE(error_of(header + "0,0,0,0,1,0,0,0,0,0,1e300,0,0,0,0\n")
                .find("session.csv:2: column 11 (vz)"),
            std::string::npos);
  EXPECT_NE(
      error_of(header + "0,0,0,0,1,0,0,0,0,0,0,0,0,-2e4,0\n").find("session.csv:2: column 14 (fy)"),
      std::string::npos);
  EXPECT_NE(error_of(header + "1e12,0,0,0,1,0,0,0,0,0,0,0,0,0,0\n")
                .find("session.csv:2: column 1 (time_s)"),
            std::string::npos);
  EXPECT_NE(error_of(header + "0,0,0,0,0,0,0,0,0,0,0,0,0,0,0\n")
                .find("session.csv:2: the orientation (qw qx qy qz) has norm 0"),
            std::string::npos);
}

TEST(DeviceLog, MissingFileIsAnInputError) {
  EXPECT_THROW(read_device_log("/nonexistent/tacta/session.csv"), InputError);
}

TEST(DeviceLogRecorder, RingKeepsTheNewestAndCountsOverwrites) {
  DeviceLogRecorder recorder(3);
  for (int i = 0; i < 5; ++i) recorder.record(awkward_sample(i));
  ASSERT_EQ(recorder.size(), 3u);
  EXPECT_EQ(recorder.overwritten_count(), 2u);
  EXPECT_EQ(recorder.at(0).time, awkward_sample(2).time);
  EXPECT_EQ(recorder.at(2).time, awkward_sample(4).time);
}

}  // namespace
}  // namespace tacta
