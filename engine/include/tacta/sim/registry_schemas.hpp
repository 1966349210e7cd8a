// The scene loader's schema lookup, answered by the plugin registry.
#pragma once

#include "tacta/plugin_registry.hpp"
#include "tacta/scene_loader.hpp"

namespace tacta {

class RegistrySchemas final : public SchemaLookup {
 public:
  explicit RegistrySchemas(const PluginRegistry& registry) : registry_(registry) {}
  std::optional<std::span<const tacta_param_spec>> schema(tacta_kind kind,
                                                          std::string_view name) const override {
    return registry_.schema(kind, name);
  }
  std::vector<std::string> names(tacta_kind kind) const override {
    std::vector<std::string> out;
    for (const LoadedDescriptor& d : registry_.list())
      if (d.descriptor->kind == kind) out.emplace_back(d.descriptor->name);
    return out;
  }

 private:
  const PluginRegistry& registry_;
};

}  // namespace tacta
