// A small streaming JSON writer: values go straight to an std::ostream as they are written, with
// commas, nesting and indentation handled here. Strings are escaped (quotes, backslash, control
// characters as \u00XX; UTF-8 passes through); doubles are written with %.17g so they read back
// bit for bit; NaN and infinities, which JSON cannot hold, are written as null.
//
//   JsonWriter json(std::cout);
//   json.begin_object();
//   json.key("ticks").value(1000);
//   json.key("bodies").begin_array(); ... json.end_array();
//   json.end_object();
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace tacta {

class JsonWriter {
 public:
  // indent: spaces per nesting level; 0 writes everything on one line.
  explicit JsonWriter(std::ostream& out, int indent = 2);
  ~JsonWriter();  // adds a final newline once the outermost value is complete
  JsonWriter(const JsonWriter&) = delete;
  JsonWriter& operator=(const JsonWriter&) = delete;

  JsonWriter& begin_object();
  JsonWriter& end_object();
  JsonWriter& begin_array();
  JsonWriter& end_array();
  // The next value's name; only inside an object. Throws std::logic_error when misplaced.
  JsonWriter& key(std::string_view name);

  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text);  // nullptr writes null
  JsonWriter& value(const std::string& text) { return value(std::string_view(text)); }
  JsonWriter& value(double number);  // %.17g; NaN/inf -> null
  JsonWriter& value(int64_t number);
  JsonWriter& value(uint64_t number);
  JsonWriter& value(int number) { return value(static_cast<int64_t>(number)); }
  JsonWriter& value(unsigned number) { return value(static_cast<uint64_t>(number)); }
  JsonWriter& value(bool flag);
  JsonWriter& null();

  // key(name).value(v) in one call.
  template <class T>
  JsonWriter& field(std::string_view name, const T& v) {
    key(name);
    return value(v);
  }

  // True once every opened object and array is closed and one top-level value was written.
  bool complete() const { return stack_.empty() && wrote_top_level_; }

  // The escaped, quoted form of text, e.g. for tests and for hand-written JSON fragments.
  static std::string quote(std::string_view text);
  // The JSON form of a double: %.17g, or null when not finite.
  static std::string number(double value);

 private:
  enum class Scope : uint8_t { Object, Array };
  void before_value();  // comma, newline and indentation as the scope needs
  void newline_indent();
  void open(Scope scope, char bracket);
  void close(Scope scope, char bracket);

  std::ostream& out_;
  int indent_;
  struct Level {
    Scope scope;
    bool empty = true;
    bool awaiting_value = false;  // objects: a key was written, its value comes next
  };
  std::vector<Level> stack_;
  bool wrote_top_level_ = false;
};

}  // namespace tacta
