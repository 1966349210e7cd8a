// The engine's one message sink: the default stderr lines, an installed sink, the threshold.
#include <gtest/gtest.h>
#include <string>
#include <utility>
#include <vector>

#include "tacta/log.hpp"

namespace {

using tacta::LogLevel;

class Log : public ::testing::Test {
 protected:
  void TearDown() override {
    tacta::set_log_sink(nullptr);
    tacta::set_log_level(LogLevel::info);
  }
};

TEST_F(Log, DefaultSinkPrefixesWarningsAndErrorsOnStderr) {
  tacta::set_log_level(LogLevel::info);
  ::testing::internal::CaptureStderr();
  tacta::log_info("running beam");
  tacta::log_warning("the surface is not closed");
  tacta::log_error("runtime fault: body square");
  EXPECT_EQ(
      ::testing::internal::GetCapturedStderr(),
      "running beam\nwarning: the surface is not closed\nerror: runtime fault: body square\n");
}

TEST_F(Log, InstalledSinkGetsEveryMessageAtOrAboveTheThreshold) {
  std::vector<std::pair<LogLevel, std::string>> seen;
  tacta::set_log_sink(
      [&](LogLevel level, const std::string& text) { seen.emplace_back(level, text); });
  tacta::set_log_level(LogLevel::warning);  // what `tacta run -q` asks for
  ::testing::internal::CaptureStderr();
  tacta::log_info("dropped");
  tacta::log_warning("kept");
  tacta::log_error("also kept");
  tacta::log(LogLevel::debug, "dropped too");
  EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");  // nothing bypasses the sink
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0], std::make_pair(LogLevel::warning, std::string("kept")));
  EXPECT_EQ(seen[1], std::make_pair(LogLevel::error, std::string("also kept")));
  EXPECT_EQ(tacta::log_level(), LogLevel::warning);
}

TEST_F(Log, LevelNamesReadBack) {
  for (LogLevel level :
       {LogLevel::debug, LogLevel::info, LogLevel::warning, LogLevel::error, LogLevel::off})
    EXPECT_EQ(tacta::log_level_named(tacta::log_level_name(level)), level);
  EXPECT_FALSE(tacta::log_level_named("loud").has_value());
}

}  // namespace
