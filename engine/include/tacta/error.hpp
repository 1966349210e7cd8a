// Load-time errors: bad scene, mesh or plugin. They carry the place (file, line, column, key path)
// and what was expected against what was found, and make `tacta` exit with code 2. Nothing here is
// thrown from the 1 kHz path, which reports faults through status bits instead.
#pragma once

#include <stdexcept>
#include <string>

namespace tacta {

struct SourceLocation {
  std::string file;      // path as the user gave it
  int line = 0;          // 1-based; 0 when unknown
  int column = 0;        // 1-based; 0 when unknown
  std::string key_path;  // e.g. "bodies[0].material.E"; empty when not in a scene
};

class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& what)
      : std::runtime_error(format(where, what)), where_(std::move(where)) {}
  const SourceLocation& where() const noexcept { return where_; }

 private:
  static std::string format(const SourceLocation& w, const std::string& what) {
    std::string s = w.file.empty() ? std::string("<input>") : w.file;
    if (w.line > 0) {
      s += ":" + std::to_string(w.line);
      if (w.column > 0) s += ":" + std::to_string(w.column);
    }
    s += ": ";
    if (!w.key_path.empty()) s += w.key_path + ": ";
    return s + what;
  }
  SourceLocation where_;
};

}  // namespace tacta
