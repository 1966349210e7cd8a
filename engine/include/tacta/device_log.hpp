// Device session log: one CSV file per device session, written by the engine's recorder and read
// by the replay device plugin (header-only because plugins may include only public headers).
//
// Format (text, one sample per line, '\n' line ends, a trailing '\r' is tolerated):
//   line 1: the header, exactly
//     time_s,px,py,pz,qw,qx,qy,qz,vx,vy,vz,buttons,fx,fy,fz
//   then one line per sample:
//     time_s       s, the device's timestamp; non-decreasing down the file
//     px py pz     m, stylus position, world frame
//     qw qx qy qz  orientation quaternion (w first), as the device reported it
//     vx vy vz     m/s, stylus velocity
//     buttons      unsigned integer, bit i = button i pressed
//     fx fy fz     N, the force sent to the device for this tick (after limiting)
// Numbers are written with %.17g, which round-trips every finite double exactly, so a replay
// returns the recorded samples bit for bit. The reader validates every line (15 columns, finite
// numbers within the bounds below, a unit quaternion, integer buttons, non-decreasing time) and
// throws tacta::InputError naming file:line and what was expected; it never crashes on
// truncated or malformed input.
//
// Allocation policy for the 1 kHz path: DeviceLogRecorder preallocates its whole capacity at
// construction; record() only copies a sample into that ring (no allocation, no lock, no I/O) and
// write_csv() is called outside the haptic loop (after the run, or from a non-real-time thread
// between runs). When the capacity is exceeded, the oldest samples are overwritten and
// overwritten_count() says how many were lost, so nothing stalls the loop.
#pragma once

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "tacta/error.hpp"

namespace tacta {

struct DeviceLogSample {
  double time = 0.0;                             // s
  double position[3] = {0.0, 0.0, 0.0};          // m
  double orientation[4] = {1.0, 0.0, 0.0, 0.0};  // w, x, y, z
  double velocity[3] = {0.0, 0.0, 0.0};          // m/s
  uint32_t buttons = 0;                          // bit i = button i
  double force[3] = {0.0, 0.0, 0.0};             // N, force sent
};

inline constexpr const char* kDeviceLogHeader =
    "time_s,px,py,pz,qw,qx,qy,qz,vx,vy,vz,buttons,fx,fy,fz";
inline constexpr int kDeviceLogColumns = 15;
// Values no haptic device produces, refused as a corrupt log (a sample at px = 1e30 once replayed
// as 1.3e29 J of injected energy). The replay device also checks positions against its workspace.
inline constexpr double kDeviceLogMaxTime = 1e9;      // s, |time_s| (about 32 years)
inline constexpr double kDeviceLogMaxPosition = 1e3;  // m, |px|, |py|, |pz| from the world origin
inline constexpr double kDeviceLogMaxSpeed =
    100.0;                                         // m/s, |vx|, |vy|, |vz|; a hand moves a few m/s
inline constexpr double kDeviceLogMaxForce = 1e4;  // N, |fx|, |fy|, |fz|; desk devices give a few N
inline constexpr double kDeviceLogQuaternionSlack = 0.01;  // |q| must lie within 1 +- this
// Longest row: 14 numbers of at most 24 characters, a 10-digit integer, 14 commas, '\n', NUL.
inline constexpr size_t kDeviceLogRowCapacity = 14 * 24 + 10 + 14 + 2;

// Formats one sample as a CSV row ending in '\n' into buffer (no allocation). Returns the number
// of characters written, or 0 if the buffer is too small.
inline size_t format_device_log_row(const DeviceLogSample& s, char* buffer,
                                    size_t capacity) noexcept {
  const int n = std::snprintf(
      buffer, capacity,
      "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%u,%.17g,%.17g,%.17g\n",
      s.time, s.position[0], s.position[1], s.position[2], s.orientation[0], s.orientation[1],
      s.orientation[2], s.orientation[3], s.velocity[0], s.velocity[1], s.velocity[2],
      static_cast<unsigned>(s.buttons), s.force[0], s.force[1], s.force[2]);
  if (n < 0 || static_cast<size_t>(n) >= capacity) return 0;
  return static_cast<size_t>(n);
}

// Writes samples to path with the header. Not for the 1 kHz path. Throws InputError on I/O failure.
inline void write_device_log(const std::string& path, const DeviceLogSample* samples,
                             size_t count) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) throw InputError({path, 0, 0, {}}, "cannot open the device log for writing");
  bool ok = std::fprintf(file, "%s\n", kDeviceLogHeader) > 0;
  char row[kDeviceLogRowCapacity];
  for (size_t i = 0; ok && i < count; ++i) {
    const size_t n = format_device_log_row(samples[i], row, sizeof row);
    ok = n > 0 && std::fwrite(row, 1, n, file) == n;
  }
  ok = (std::fclose(file) == 0) && ok;
  if (!ok) throw InputError({path, 0, 0, {}}, "writing the device log failed (disk full?)");
}

// Fixed-capacity ring of samples for the haptic loop; see the allocation policy above.
class DeviceLogRecorder {
 public:
  explicit DeviceLogRecorder(size_t capacity) : ring_(capacity == 0 ? 1 : capacity) {}

  // 1 kHz path: copies one sample; never allocates.
  void record(const DeviceLogSample& sample) noexcept {
    ring_[(first_ + count_) % ring_.size()] = sample;
    if (count_ < ring_.size()) {
      ++count_;
    } else {
      first_ = (first_ + 1) % ring_.size();
      ++overwritten_;
    }
  }
  size_t size() const noexcept { return count_; }
  size_t capacity() const noexcept { return ring_.size(); }
  uint64_t overwritten_count() const noexcept { return overwritten_; }
  const DeviceLogSample& at(size_t i) const noexcept { return ring_[(first_ + i) % ring_.size()]; }
  void clear() noexcept {
    first_ = count_ = 0;
    overwritten_ = 0;
  }

  // Outside the 1 kHz path: writes the recorded samples, oldest first.
  void write_csv(const std::string& path) const {
    std::vector<DeviceLogSample> ordered;
    ordered.reserve(count_);
    for (size_t i = 0; i < count_; ++i) ordered.push_back(at(i));
    write_device_log(path, ordered.data(), ordered.size());
  }

 private:
  std::vector<DeviceLogSample> ring_;
  size_t first_ = 0;
  size_t count_ = 0;
  uint64_t overwritten_ = 0;
};

namespace device_log_detail {

inline std::string_view trim_line_end(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

inline const char* column_name(int index) {
  static const char* const names[kDeviceLogColumns] = {"time_s", "px",      "py", "pz", "qw",
                                                       "qx",     "qy",      "qz", "vx", "vy",
                                                       "vz",     "buttons", "fx", "fy", "fz"};
  return names[index];
}

// The bound of column `index` (see kDeviceLog*) and its unit.
struct ColumnBound {
  double bound;
  const char* unit;
};
inline ColumnBound column_bound(int index) {
  if (index == 0) return {kDeviceLogMaxTime, "s"};
  if (index <= 3) return {kDeviceLogMaxPosition, "m"};
  if (index <= 7) return {1.0 + kDeviceLogQuaternionSlack, ""};
  if (index <= 10) return {kDeviceLogMaxSpeed, "m/s"};
  return {kDeviceLogMaxForce, "N"};
}

// What is implausible in a parsed sample, or an empty string.
inline std::string implausible(const DeviceLogSample& s) {
  const double values[kDeviceLogColumns] = {s.time,           s.position[0],    s.position[1],
                                            s.position[2],    s.orientation[0], s.orientation[1],
                                            s.orientation[2], s.orientation[3], s.velocity[0],
                                            s.velocity[1],    s.velocity[2],    0.0,
                                            s.force[0],       s.force[1],       s.force[2]};
  char text[200];
  for (int i = 0; i < kDeviceLogColumns; ++i) {
    const ColumnBound limit = column_bound(i);
    if (std::abs(values[i]) <= limit.bound) continue;
    std::snprintf(
        text, sizeof text,
        "column %d (%s) = %.9g is beyond %g %s: no haptic device gives that (corrupt log?)", i + 1,
        column_name(i), values[i], limit.bound, limit.unit);
    return text;
  }
  const double norm =
      std::sqrt(s.orientation[0] * s.orientation[0] + s.orientation[1] * s.orientation[1] +
                s.orientation[2] * s.orientation[2] + s.orientation[3] * s.orientation[3]);
  if (std::abs(norm - 1.0) > kDeviceLogQuaternionSlack) {
    std::snprintf(text, sizeof text,
                  "the orientation (qw qx qy qz) has norm %.9g; expected a unit quaternion", norm);
    return text;
  }
  return {};
}

// Parses one data line into sample; returns an empty string or what was wrong.
inline std::string parse_row(std::string_view line, DeviceLogSample& s) {
  double* targets[kDeviceLogColumns] = {
      &s.time,           &s.position[0],    &s.position[1],    &s.position[2], &s.orientation[0],
      &s.orientation[1], &s.orientation[2], &s.orientation[3], &s.velocity[0], &s.velocity[1],
      &s.velocity[2],    nullptr,           &s.force[0],       &s.force[1],    &s.force[2]};
  int column = 0;
  size_t start = 0;
  while (true) {
    const size_t comma = line.find(',', start);
    const std::string_view field = line.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
    if (column >= kDeviceLogColumns)
      return "expected " + std::to_string(kDeviceLogColumns) + " columns, found more";
    const std::string text(field);
    if (text.empty() || text.find_first_of(" \t") != std::string::npos)
      return std::string("expected a number in column ") + std::to_string(column + 1) + " (" +
             column_name(column) + "), found '" + text + "'";
    char* end = nullptr;
    errno = 0;
    if (targets[column] == nullptr) {
      const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
      if (*end != '\0' || errno != 0 || text[0] == '-' || value > 0xffffffffull)
        return "expected an unsigned 32-bit integer in column 12 (buttons), found '" + text + "'";
      s.buttons = static_cast<uint32_t>(value);
    } else {
      const double value = std::strtod(text.c_str(), &end);
      if (*end != '\0' || !std::isfinite(value))
        return std::string("expected a finite number in column ") + std::to_string(column + 1) +
               " (" + column_name(column) + "), found '" + text + "'";
      *targets[column] = value;
    }
    ++column;
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (column != kDeviceLogColumns)
    return "expected " + std::to_string(kDeviceLogColumns) + " columns, found " +
           std::to_string(column) + " (truncated line?)";
  return implausible(s);
}

}  // namespace device_log_detail

// Parses log text; file names the source in errors. Throws InputError with file:line.
inline std::vector<DeviceLogSample> parse_device_log(std::string_view text,
                                                     const std::string& file) {
  std::vector<DeviceLogSample> samples;
  size_t start = 0;
  int line_number = 0;
  bool header_seen = false;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = device_log_detail::trim_line_end(text.substr(start, end - start));
    start = end + 1;
    ++line_number;
    if (!header_seen) {
      if (line != kDeviceLogHeader)
        throw InputError({file, line_number, 0, {}},
                         std::string("expected the device log header '") + kDeviceLogHeader +
                             "', found '" + std::string(line.substr(0, 80)) + "'");
      header_seen = true;
      continue;
    }
    if (line.empty()) {
      // Only trailing empty lines are allowed.
      if (text.find_first_not_of("\r\n", start) == std::string_view::npos) break;
      throw InputError({file, line_number, 0, {}}, "expected a sample, found an empty line");
    }
    DeviceLogSample sample;
    const std::string problem = device_log_detail::parse_row(line, sample);
    if (!problem.empty()) throw InputError({file, line_number, 0, {}}, problem);
    if (!samples.empty() && sample.time < samples.back().time)
      throw InputError({file, line_number, 0, {}}, "expected non-decreasing time_s, found " +
                                                       std::to_string(sample.time) + " after " +
                                                       std::to_string(samples.back().time));
    samples.push_back(sample);
  }
  if (!header_seen)
    throw InputError({file, 1, 0, {}}, std::string("expected the device log header '") +
                                           kDeviceLogHeader + "', found an empty file");
  return samples;
}

// Reads and validates a log file. Throws InputError (file:line: what was expected).
inline std::vector<DeviceLogSample> read_device_log(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError({path, 0, 0, {}}, "cannot open the device log (expected a CSV file)");
  std::ostringstream content;
  content << in.rdbuf();
  return parse_device_log(content.str(), path);
}

}  // namespace tacta
