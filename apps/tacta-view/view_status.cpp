#include "view_status.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace tacta::view {
namespace {

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (const char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) {
      char code[8];
      std::snprintf(code, sizeof code, "\\u%04x", c);
      out += code;
    } else {
      out += c;
    }
  }
  return out + "\"";
}

std::string list(const std::vector<std::string>& items) {
  std::string out = "[";
  for (size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + quoted(items[i]);
  return out + "]";
}

std::string vec3(const std::array<double, 3>& v) {
  char text[96];
  std::snprintf(text, sizeof text, "[%.9g, %.9g, %.9g]", v[0], v[1], v[2]);
  return text;
}

}  // namespace

void write_view_status(const std::string& path, const ViewStatus& s) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write the status file " + path);
  char number[64];
  out << "{\n  \"frames\": " << s.frames << ",\n";
  std::snprintf(number, sizeof number, "%.9g", s.sim_time_s);
  out << "  \"sim_time_s\": " << number << ",\n";
  std::snprintf(number, sizeof number, "%.9g", s.wall_time_s);
  out << "  \"wall_time_s\": " << number << ",\n";
  out << "  \"marks\": [";
  for (size_t i = 0; i < s.marks.size(); ++i) {
    std::snprintf(number, sizeof number, "%s[%.0f, %.9g]", i ? ", " : "", s.marks[i][0],
                  s.marks[i][1]);
    out << number;
  }
  out << "],\n";
  out << "  \"swaps_requested\": " << s.swaps_requested << ",\n";
  out << "  \"swap_history\": " << list(s.swap_history) << ",\n";
  out << "  \"body_models\": " << list(s.body_models) << ",\n";
  out << "  \"body_frozen\": [";
  for (size_t i = 0; i < s.body_frozen.size(); ++i)
    out << (i ? ", " : "") << (s.body_frozen[i] ? "true" : "false");
  out << "],\n";
  std::snprintf(number, sizeof number, "%.9g", s.max_force_N);
  out << "  \"max_force_N\": " << number << ",\n";
  out << "  \"mouse\": " << (s.mouse ? "true" : "false") << ",\n";
  out << "  \"mouse_target\": " << vec3(s.mouse_target) << ",\n";
  out << "  \"stylus\": " << vec3(s.stylus) << ",\n";
  out << "  \"script_failures\": " << list(s.script_failures) << ",\n";
  out << "  \"model_error\": " << quoted(s.model_error) << ",\n";
  out << "  \"run_error\": " << quoted(s.run_error) << "\n}\n";
  if (!out) throw std::runtime_error("cannot write the status file " + path);
}

}  // namespace tacta::view
