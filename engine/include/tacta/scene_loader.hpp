// Loading a scene: YAML text -> a fully validated SceneDesc (see docs/SCENES.md for the format).
// Every problem is a tacta::InputError naming file:line:column, the key path, what was expected
// and what was found; nothing is returned half-checked. Plugin parameters are validated against
// the schemas a SchemaLookup provides, so the loader does not depend on the plugin loader itself.
#pragma once

#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "tacta/plugin.h"
#include "tacta/scene.hpp"

namespace tacta {

// Where the loader finds plugin parameter schemas: the plugin registry at run time, a table of
// hand-written schemas in tests.
class SchemaLookup {
 public:
  virtual ~SchemaLookup() = default;
  // The parameter schema of plugin `name` of `kind` (TACTA_KIND_MODEL, _COLLISION, _DEVICE), or
  // nullopt when no such plugin is registered. The span must outlive the load call.
  virtual std::optional<std::span<const tacta_param_spec>> schema(tacta_kind kind,
                                                                  std::string_view name) const = 0;
  // Every registered plugin name of `kind`, for "unknown plugin; available: ..." messages.
  virtual std::vector<std::string> names(tacta_kind kind) const = 0;
};

// A SchemaLookup over a fixed table; the schema arrays are not copied and must outlive it.
class SchemaTable : public SchemaLookup {
 public:
  SchemaTable& add(tacta_kind kind, std::string name, std::span<const tacta_param_spec> schema) {
    entries_[{kind, std::move(name)}] = schema;
    return *this;
  }
  std::optional<std::span<const tacta_param_spec>> schema(tacta_kind kind,
                                                          std::string_view name) const override {
    auto it = entries_.find({kind, std::string(name)});
    if (it == entries_.end()) return std::nullopt;
    return it->second;
  }
  std::vector<std::string> names(tacta_kind kind) const override {
    std::vector<std::string> out;
    for (const auto& [key, schema] : entries_)
      if (key.first == kind) out.push_back(key.second);
    return out;
  }

 private:
  std::map<std::pair<tacta_kind, std::string>, std::span<const tacta_param_spec>> entries_;
};

// Reads and validates the scene file at `path`. `overrides` are "key.path=value" strings (the
// command line's --set), applied to the YAML tree before validation; see docs/SCENES.md.
SceneDesc load_scene(const std::string& path, const SchemaLookup& schemas,
                     const std::vector<std::string>& overrides = {});

// Same, from text; `virtual_path` names it in messages and its folder anchors relative paths.
SceneDesc load_scene_from_string(const std::string& text, const std::string& virtual_path,
                                 const SchemaLookup& schemas,
                                 const std::vector<std::string>& overrides = {});

// One body (the map a scene lists under `bodies`), e.g. to add while a scene runs; relative
// paths resolve against `virtual_path`'s folder (give the scene's path).
BodyDesc load_body_from_string(const std::string& text, const std::string& virtual_path,
                               const SchemaLookup& schemas);

// One shape (a device's `tool` or an obstacle's `shape`: {sphere: {radius}}, ...), e.g. to change
// a tool while a scene runs.
ShapeDesc load_shape_from_string(const std::string& text, const std::string& virtual_path,
                                 const SchemaLookup& schemas);

// Isotropic elasticity conversions (both in Pa; nu dimensionless).
struct LameParameters {
  double lambda;  // Pa
  double mu;      // Pa, the shear modulus
};
struct EngineeringConstants {
  double youngs_modulus;  // Pa
  double poisson_ratio;
};
// lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).
LameParameters lame_from_engineering(double youngs_modulus, double poisson_ratio);
// E = mu (3 lambda + 2 mu) / (lambda + mu), nu = lambda / (2 (lambda + mu)).
EngineeringConstants engineering_from_lame(double lambda, double mu);

}  // namespace tacta
