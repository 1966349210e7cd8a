// The plugin loader and registry: finds plugin shared libraries, loads them through the C ABI
// (plugin.h), validates every descriptor they register, and answers lookups by kind and name.
//
// Search order: folders given to add_first_path() (a Python package's own plugins), the build
// tree's plugin folder, the install prefix's lib/tacta/plugins, every folder in TACTA_PLUGIN_PATH
// (colon-separated), then folders given to add_path(). Every *.so
// there is opened with dlopen(RTLD_NOW | RTLD_LOCAL). A file that fails (dlopen error, no entry
// symbol, ABI refused, a malformed descriptor, a name another file registered already) is
// recorded with its reason and does not stop the others; nothing of a refused file stays
// registered. Library handles stay open until the registry is destroyed, so every instance made
// from a descriptor must be destroyed before the registry.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "tacta/plugin.h"

namespace tacta {

struct LoadedDescriptor {
  const tacta_descriptor* descriptor = nullptr;  // lives as long as the registry
  std::string file;                              // canonical path of the library
};

struct RefusedPlugin {
  std::string file;    // path of the refused library
  std::string reason;  // one line naming the cause, e.g. the missing library or function
};

class PluginRegistry {
 public:
  enum class DefaultPaths { Search, Skip };

  // Search: the build-tree, install and TACTA_PLUGIN_PATH folders are part of load().
  // Skip: only folders from add_path() (used by tests that want one folder only).
  explicit PluginRegistry(DefaultPaths defaults = DefaultPaths::Search);
  ~PluginRegistry();
  PluginRegistry(const PluginRegistry&) = delete;
  PluginRegistry& operator=(const PluginRegistry&) = delete;

  // Adds a folder searched after the defaults; throws tacta::InputError if it is not a folder.
  void add_path(const std::string& directory);
  // Adds a folder searched before the defaults (a missing one is listed and skipped): the
  // Python module's own package folder, so an installed wheel loads the plugins it carries.
  void add_first_path(const std::string& directory);

  // The folders load() scans, in order (missing default folders are listed but skipped).
  std::vector<std::string> search_paths() const;

  // Scans every search folder; may be called again after add_path() (loaded files are skipped).
  void load();
  // Loads every *.so of one folder (sorted by name), or one file. Failures go to refused().
  void load_directory(const std::string& directory);
  void load_file(const std::string& path);

  // Every registered descriptor, sorted by kind then name.
  std::vector<LoadedDescriptor> list() const;
  const std::vector<RefusedPlugin>& refused() const;

  // nullptr when no descriptor of this kind has this name.
  const LoadedDescriptor* find(tacta_kind kind, std::string_view name) const;
  // Like find(), but throws tacta::InputError with unknown_name_message() when absent.
  const LoadedDescriptor& require(tacta_kind kind, std::string_view name) const;
  // The parameter schema of (kind, name), or nullopt when there is no such descriptor.
  std::optional<std::span<const tacta_param_spec>> schema(tacta_kind kind,
                                                          std::string_view name) const;
  // "no model plugin named 'tensor_mas'; did you mean 'tensor_mass'? available: a, b, c"
  std::string unknown_name_message(tacta_kind kind, std::string_view name) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// The names among `candidates` closest to `name` by edit distance (Levenshtein), best first,
// keeping only plausible typos (distance at most a third of the longer name, and at least 1).
std::vector<std::string> closest_names(std::string_view name,
                                       const std::vector<std::string>& candidates);

}  // namespace tacta
