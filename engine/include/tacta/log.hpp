// One sink for every message the engine and the tacta CLI print (warnings, notes, plugins' log
// lines), through one spdlog logger with levels. Results a command prints (tables, JSON) are
// output, not messages, and do not come here.
//
// The default sink writes to stderr: "warning: TEXT", "error: TEXT", and info and debug as the
// bare text. A GUI or a binding installs its own sink; the threshold drops what is below it
// (default info, or TACTA_LOG_LEVEL=debug|info|warning|error|off; `tacta ... -q` sets warning).
// Not for the 1 kHz path: a message formats a string and takes the sink's lock.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>

namespace tacta {

enum class LogLevel { debug, info, warning, error, off };

// Called for each message at or above the threshold, from the thread that logged it, one call
// at a time.
using LogSink = std::function<void(LogLevel level, const std::string& message)>;

void log(LogLevel level, const std::string& message);
inline void log_info(const std::string& message) { log(LogLevel::info, message); }
inline void log_warning(const std::string& message) { log(LogLevel::warning, message); }
inline void log_error(const std::string& message) { log(LogLevel::error, message); }

// An empty sink puts the default stderr sink back.
void set_log_sink(LogSink sink);
void set_log_level(LogLevel threshold);
LogLevel log_level();

// "debug", "info", "warning", "error" or "off"; nullopt for any other name.
std::optional<LogLevel> log_level_named(std::string_view name);
const char* log_level_name(LogLevel level);

}  // namespace tacta
