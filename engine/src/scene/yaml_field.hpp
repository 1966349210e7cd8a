// A YAML node together with its key path in the scene ("bodies[1].material.poisson_ratio") and
// typed readers that turn every mismatch into an InputError with file:line:column, the path, what
// was expected and what was found. Only the scene loader uses it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "tacta/error.hpp"
#include "tacta/scene.hpp"

namespace tacta {
class SchemaLookup;
}

namespace tacta::scene_detail {

// One --set override after it was applied: the concrete key path it wrote, and its text.
struct OverrideOrigin {
  std::string key_path;  // e.g. "bodies[0].model"
  std::string text;      // e.g. "bodies.*.model=corotational_fem"
};

// What every reader of one load shares.
struct LoadContext {
  std::string file;                 // the scene path as the user gave it
  std::filesystem::path directory;  // absolute folder of the scene
  std::vector<OverrideOrigin> overrides;
  const SchemaLookup* schemas = nullptr;
};

// A closed, open or half-open interval of doubles, with the text that messages show.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;
  bool hi_open = false;

  static Range any() { return {}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range non_negative() {
    return {0.0, std::numeric_limits<double>::infinity(), false, false};
  }
  static Range closed(double a, double b) { return {a, b, false, false}; }
  static Range open(double a, double b) { return {a, b, true, true}; }
  bool contains(double x) const;
  std::string describe() const;  // "> 0", "in [0, 1]", "any finite number"
};

using KeyList = std::initializer_list<std::string_view>;

class Field {
 public:
  Field(const LoadContext& context, YAML::Node node, std::string path,
        YAML::Mark fallback = YAML::Mark::null_mark());

  const std::string& path() const { return path_; }
  const YAML::Node& yaml() const { return node_; }
  const LoadContext& context() const { return *context_; }
  bool is_map() const { return node_.IsMap(); }
  bool is_list() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  SourceLocation where() const;

  [[noreturn]] void fail(const std::string& message) const;
  // "expected <expected>, found <what this node holds>"
  [[noreturn]] void fail_expected(const std::string& expected) const;
  std::string found() const;  // a short description of the node for messages

  // Maps. `get` returns nullopt for an absent key; `require` fails naming the missing key.
  void expect_map(const std::string& what) const;
  std::optional<Field> get(std::string_view key) const;
  Field require(std::string_view key) const;
  bool has(std::string_view key) const;
  // Fails on a key outside `allowed` (with a did-you-mean hint), on a duplicate or non-text key.
  void check_keys(KeyList allowed) const;
  void check_keys(const std::vector<std::string>& allowed) const;
  // The map's keys in file order, each with a Field that points at the key itself (for errors).
  std::vector<std::pair<std::string, Field>> keys() const;

  // Lists.
  std::vector<Field> items(const std::string& what) const;

  // Scalars.
  double real(Range range = Range::any()) const;
  int64_t integer(int64_t lo, int64_t hi) const;
  uint32_t index() const { return static_cast<uint32_t>(integer(0, UINT32_MAX)); }
  bool boolean() const;
  std::string text() const;  // any non-empty scalar
  // One of `choices`; an unknown word gets a did-you-mean hint.
  std::string choice(const std::vector<std::string>& choices) const;
  Vec3 vec3(Range each = Range::any()) const;
  std::vector<double> reals(size_t count, Range each = Range::any()) const;  // count 0: any
  std::vector<uint32_t> indices() const;
  // An absolute path: a relative one is taken from the scene's folder, or from the working
  // directory when the value came from a --set override.
  std::string file_path() const;
  bool from_override() const;  // this value, or a map holding it, was written by --set

 private:
  const LoadContext* context_;
  YAML::Node node_;
  std::string path_;
  YAML::Mark mark_;  // the node's own position, else its parent's
};

// Child path helpers: "a" + "b" -> "a.b"; "a" + 2 -> "a[2]".
std::string child_path(const std::string& parent, std::string_view key);
std::string item_path(const std::string& parent, size_t index);

}  // namespace tacta::scene_detail
