// The streaming JSON writer (see tacta/json.hpp).
#include "tacta/json.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tacta {

JsonWriter::JsonWriter(std::ostream& out, int indent) : out_(out), indent_(indent) {}

JsonWriter::~JsonWriter() {
  if (complete()) out_ << '\n';
}

std::string JsonWriter::quote(std::string_view text) {
  std::string q;
  q.reserve(text.size() + 2);
  q += '"';
  for (const char c : text) {
    switch (c) {
      case '"': q += "\\\""; break;
      case '\\': q += "\\\\"; break;
      case '\n': q += "\\n"; break;
      case '\r': q += "\\r"; break;
      case '\t': q += "\\t"; break;
      case '\b': q += "\\b"; break;
      case '\f': q += "\\f"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
          q += escaped;
        } else {
          q += c;  // UTF-8 bytes pass through unchanged
        }
    }
  }
  q += '"';
  return q;
}

std::string JsonWriter::number(double v) {
  if (!std::isfinite(v)) return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

void JsonWriter::newline_indent() {
  if (indent_ <= 0) return;
  out_ << '\n';
  for (size_t i = 0; i < stack_.size() * static_cast<size_t>(indent_); ++i) out_ << ' ';
}

void JsonWriter::before_value() {
  if (stack_.empty()) {
    if (wrote_top_level_) throw std::logic_error("JsonWriter: a second top-level value");
    wrote_top_level_ = true;
    return;
  }
  Level& level = stack_.back();
  if (level.scope == Scope::Object) {
    if (!level.awaiting_value) throw std::logic_error("JsonWriter: value without key in an object");
    level.awaiting_value = false;
    return;
  }
  if (!level.empty) out_ << ',';
  level.empty = false;
  newline_indent();
}

JsonWriter& JsonWriter::key(std::string_view name) {
  if (stack_.empty() || stack_.back().scope != Scope::Object || stack_.back().awaiting_value)
    throw std::logic_error("JsonWriter: key '" + std::string(name) + "' outside an object");
  Level& level = stack_.back();
  if (!level.empty) out_ << ',';
  level.empty = false;
  newline_indent();
  out_ << quote(name) << (indent_ > 0 ? ": " : ":");
  level.awaiting_value = true;
  return *this;
}

void JsonWriter::open(Scope scope, char bracket) {
  before_value();
  out_ << bracket;
  stack_.push_back({scope});
}

void JsonWriter::close(Scope scope, char bracket) {
  if (stack_.empty() || stack_.back().scope != scope || stack_.back().awaiting_value)
    throw std::logic_error(std::string("JsonWriter: unbalanced '") + bracket + "'");
  const bool was_empty = stack_.back().empty;
  stack_.pop_back();
  if (!was_empty) newline_indent();
  out_ << bracket;
}

JsonWriter& JsonWriter::begin_object() {
  open(Scope::Object, '{');
  return *this;
}
JsonWriter& JsonWriter::end_object() {
  close(Scope::Object, '}');
  return *this;
}
JsonWriter& JsonWriter::begin_array() {
  open(Scope::Array, '[');
  return *this;
}
JsonWriter& JsonWriter::end_array() {
  close(Scope::Array, ']');
  return *this;
}

JsonWriter& JsonWriter::value(std::string_view text) {
  before_value();
  out_ << quote(text);
  return *this;
}
JsonWriter& JsonWriter::value(const char* text) {
  return text ? value(std::string_view(text)) : null();
}
JsonWriter& JsonWriter::value(double v) {
  before_value();
  out_ << number(v);
  return *this;
}
JsonWriter& JsonWriter::value(int64_t v) {
  before_value();
  out_ << v;
  return *this;
}
JsonWriter& JsonWriter::value(uint64_t v) {
  before_value();
  out_ << v;
  return *this;
}
JsonWriter& JsonWriter::value(bool flag) {
  before_value();
  out_ << (flag ? "true" : "false");
  return *this;
}
JsonWriter& JsonWriter::null() {
  before_value();
  out_ << "null";
  return *this;
}

}  // namespace tacta
