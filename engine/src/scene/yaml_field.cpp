// Typed, located reading of scene YAML nodes.
#include "scene/yaml_field.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fmt/format.h>
#include <set>

#include "scene/did_you_mean.hpp"

namespace tacta::scene_detail {

namespace {

bool is_path_prefix(const std::string& prefix, const std::string& path) {
  if (path.size() < prefix.size() || path.compare(0, prefix.size(), prefix) != 0) return false;
  return path.size() == prefix.size() || path[prefix.size()] == '.' || path[prefix.size()] == '[';
}

std::optional<double> parse_real(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::optional<int64_t> parse_integer(std::string_view text) {
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  int64_t value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::string number_text(double x) { return fmt::format("{}", x); }

}  // namespace

std::string child_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : parent + "." + std::string(key);
}

std::string item_path(const std::string& parent, size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

bool Range::contains(double x) const {
  if (!std::isfinite(x)) return false;
  if (lo_open ? !(x > lo) : !(x >= lo)) return false;
  if (hi_open ? !(x < hi) : !(x <= hi)) return false;
  return true;
}

std::string Range::describe() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (!has_lo && !has_hi) return "";
  if (!has_hi) return (lo_open ? "> " : ">= ") + number_text(lo);
  if (!has_lo) return (hi_open ? "< " : "<= ") + number_text(hi);
  return std::string("in ") + (lo_open ? "(" : "[") + number_text(lo) + ", " + number_text(hi) +
         (hi_open ? ")" : "]");
}

Field::Field(const LoadContext& context, YAML::Node node, std::string path, YAML::Mark fallback)
    : context_(&context), node_(std::move(node)), path_(std::move(path)), mark_(fallback) {
  if (node_.IsDefined() && !node_.Mark().is_null()) mark_ = node_.Mark();
}

SourceLocation Field::where() const {
  // A value written by --set is reported at that override, not at the file position it replaced.
  for (auto it = context_->overrides.rbegin(); it != context_->overrides.rend(); ++it)
    if (is_path_prefix(it->key_path, path_))
      return SourceLocation{"--set " + it->text, 0, 0, path_};
  SourceLocation where{context_->file, 0, 0, path_};
  if (!mark_.is_null()) {
    where.line = mark_.line + 1;  // yaml-cpp marks are 0-based
    where.column = mark_.column + 1;
  }
  return where;
}

void Field::fail(const std::string& message) const { throw InputError(where(), message); }

void Field::fail_expected(const std::string& expected) const {
  fail("expected " + expected + ", found " + found());
}

std::string Field::found() const {
  if (!node_.IsDefined()) return "nothing";
  switch (node_.Type()) {
    case YAML::NodeType::Null: return "nothing (an empty value)";
    case YAML::NodeType::Scalar: {
      std::string text = node_.Scalar();
      if (text.size() > 60) text = text.substr(0, 57) + "...";
      return "'" + text + "'";
    }
    case YAML::NodeType::Sequence:
      return "a list of " + std::to_string(node_.size()) + (node_.size() == 1 ? " item" : " items");
    case YAML::NodeType::Map: {
      std::vector<std::string> names;
      for (const auto& entry : node_)
        names.push_back(entry.first.IsScalar() ? entry.first.Scalar() : std::string("?"));
      return "a map (keys: " + join(names) + ")";
    }
    default: return "nothing";
  }
}

void Field::expect_map(const std::string& what) const {
  if (!node_.IsMap()) fail_expected(what);
}

std::optional<Field> Field::get(std::string_view key) const {
  if (!node_.IsMap()) fail_expected("a map");
  for (const auto& entry : node_)
    if (entry.first.IsScalar() && entry.first.Scalar() == key)
      return Field(*context_, entry.second, child_path(path_, key), entry.first.Mark());
  return std::nullopt;
}

bool Field::has(std::string_view key) const { return get(key).has_value(); }

Field Field::require(std::string_view key) const {
  if (auto child = get(key)) return *child;
  Field missing(*context_, YAML::Node(), child_path(path_, key), mark_);
  missing.fail("missing required key '" + std::string(key) + "'");
}

std::vector<std::pair<std::string, Field>> Field::keys() const {
  if (!node_.IsMap()) fail_expected("a map");
  std::vector<std::pair<std::string, Field>> out;
  for (const auto& entry : node_) {
    if (!entry.first.IsScalar()) Field(*context_, entry.first, path_, mark_).fail_expected("a key");
    const std::string name = entry.first.Scalar();
    out.emplace_back(name, Field(*context_, entry.first, child_path(path_, name), mark_));
  }
  return out;
}

void Field::check_keys(KeyList allowed) const {
  check_keys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void Field::check_keys(const std::vector<std::string>& allowed) const {
  std::set<std::string> seen;
  for (const auto& [name, key] : keys()) {
    if (!seen.insert(name).second) key.fail("duplicate key '" + name + "'");
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end())
      key.fail(unknown_name_message("key", name, allowed));
  }
}

std::vector<Field> Field::items(const std::string& what) const {
  if (!node_.IsSequence()) fail_expected(what);
  std::vector<Field> out;
  for (size_t i = 0; i < node_.size(); ++i)
    out.emplace_back(*context_, node_[i], item_path(path_, i), mark_);
  return out;
}

double Field::real(Range range) const {
  const std::string expected =
      "a number" + (range.describe().empty() ? "" : " " + range.describe());
  if (!node_.IsScalar()) fail_expected(expected);
  auto value = parse_real(node_.Scalar());
  if (!value || !range.contains(*value)) fail_expected(expected);
  return *value;
}

int64_t Field::integer(int64_t lo, int64_t hi) const {
  const std::string expected = hi == INT64_MAX ? fmt::format("an integer >= {}", lo)
                                               : fmt::format("an integer in [{}, {}]", lo, hi);
  if (!node_.IsScalar()) fail_expected(expected);
  auto value = parse_integer(node_.Scalar());
  if (!value || *value < lo || *value > hi) fail_expected(expected);
  return *value;
}

bool Field::boolean() const {
  if (node_.IsScalar()) {
    std::string word = node_.Scalar();
    std::transform(word.begin(), word.end(), word.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (word == "true" || word == "yes" || word == "on") return true;
    if (word == "false" || word == "no" || word == "off") return false;
  }
  fail_expected("true or false");
}

std::string Field::text() const {
  if (!node_.IsScalar() || node_.Scalar().empty()) fail_expected("a text value");
  return node_.Scalar();
}

std::string Field::choice(const std::vector<std::string>& choices) const {
  if (!node_.IsScalar()) fail_expected("one of: " + join(choices));
  const std::string word = node_.Scalar();
  if (std::find(choices.begin(), choices.end(), word) == choices.end())
    fail(unknown_name_message("value", word, choices));
  return word;
}

Vec3 Field::vec3(Range each) const {
  const std::vector<double> v = reals(3, each);
  return {v[0], v[1], v[2]};
}

std::vector<double> Field::reals(size_t count, Range each) const {
  const std::string element = "numbers" + (each.describe().empty() ? "" : " " + each.describe());
  const std::string expected =
      count == 0 ? "a list of " + element : fmt::format("a list of {} {}", count, element);
  if (!node_.IsSequence() || (count != 0 && node_.size() != count)) fail_expected(expected);
  std::vector<double> out;
  for (const Field& item : items(expected)) out.push_back(item.real(each));
  return out;
}

std::vector<uint32_t> Field::indices() const {
  std::vector<uint32_t> out;
  for (const Field& item : items("a list of node indices")) out.push_back(item.index());
  return out;
}

bool Field::from_override() const {
  for (const OverrideOrigin& origin : context_->overrides)
    if (is_path_prefix(origin.key_path, path_)) return true;
  return false;
}

std::string Field::file_path() const {
  std::filesystem::path path(text());
  // A path typed on the command line (--set) is relative to where the command runs.
  if (path.is_relative())
    path = (from_override() ? std::filesystem::current_path() : context_->directory) / path;
  return path.lexically_normal().string();
}

}  // namespace tacta::scene_detail
