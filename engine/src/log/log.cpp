#include "tacta/log.hpp"

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <spdlog/logger.h>
#include <spdlog/sinks/base_sink.h>

namespace tacta {

namespace {

constexpr const char* kNames[] = {"debug", "info", "warning", "error", "off"};

LogLevel from_spdlog(spdlog::level::level_enum level) {
  switch (level) {
    case spdlog::level::trace:
    case spdlog::level::debug: return LogLevel::debug;
    case spdlog::level::info: return LogLevel::info;
    case spdlog::level::warn: return LogLevel::warning;
    default: return LogLevel::error;
  }
}

spdlog::level::level_enum to_spdlog(LogLevel level) {
  switch (level) {
    case LogLevel::debug: return spdlog::level::debug;
    case LogLevel::info: return spdlog::level::info;
    case LogLevel::warning: return spdlog::level::warn;
    case LogLevel::error: return spdlog::level::err;
    case LogLevel::off: break;
  }
  return spdlog::level::off;
}

// What the CLI always printed: a "warning: " or "error: " prefix, info and debug bare.
void write_to_stderr(LogLevel level, const std::string& message) {
  const char* prefix = level == LogLevel::warning ? "warning: "
                       : level == LogLevel::error ? "error: "
                                                  : "";
  std::fprintf(stderr, "%s%s\n", prefix, message.c_str());
}

// Hands each message to the installed sink; spdlog's base_sink serialises the calls.
class ForwardingSink : public spdlog::sinks::base_sink<std::mutex> {
 public:
  void set(LogSink replacement) {
    std::lock_guard<std::mutex> lock(mutex_);
    sink_ = std::move(replacement);
  }

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    const std::string text(msg.payload.data(), msg.payload.size());
    if (sink_)
      sink_(from_spdlog(msg.level), text);
    else
      write_to_stderr(from_spdlog(msg.level), text);
  }
  void flush_() override {}

 private:
  LogSink sink_;
};

struct Logger {
  std::shared_ptr<ForwardingSink> sink = std::make_shared<ForwardingSink>();
  spdlog::logger logger{"tacta", sink};
  Logger() {
    const char* env = std::getenv("TACTA_LOG_LEVEL");
    const std::optional<LogLevel> named = log_level_named(env ? env : "");
    logger.set_level(to_spdlog(named.value_or(LogLevel::info)));
  }
};

Logger& instance() {
  static Logger logger;
  return logger;
}

}  // namespace

void log(LogLevel level, const std::string& message) {
  if (level == LogLevel::off) return;
  instance().logger.log(to_spdlog(level), "{}", message);
}

void set_log_sink(LogSink sink) { instance().sink->set(std::move(sink)); }

void set_log_level(LogLevel threshold) { instance().logger.set_level(to_spdlog(threshold)); }

LogLevel log_level() {
  const auto level = instance().logger.level();
  return level == spdlog::level::off ? LogLevel::off : from_spdlog(level);
}

std::optional<LogLevel> log_level_named(std::string_view name) {
  for (int i = 0; i < 5; ++i)
    if (name == kNames[i]) return static_cast<LogLevel>(i);
  return std::nullopt;
}

const char* log_level_name(LogLevel level) { return kNames[static_cast<int>(level)]; }

}  // namespace tacta
