// The plugin loader: dlopen, the entry call with a validating host table, and the bookkeeping of
// what each file registered or why it was refused.
#include "tacta/plugin_registry.hpp"

#include <algorithm>
#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <set>
#include <unistd.h>

#include "plugin/descriptor_check.hpp"
#include "tacta/error.hpp"
#include "tacta/log.hpp"

namespace tacta {

namespace fs = std::filesystem;

struct PluginRegistry::State {
  DefaultPaths defaults = DefaultPaths::Search;
  std::vector<std::string> first_paths;  // before the defaults
  std::vector<std::string> added_paths;
  std::set<std::string> seen_files;  // canonical paths already tried, loaded or refused
  std::vector<void*> handles;        // open libraries, closed by ~PluginRegistry
  std::vector<LoadedDescriptor> entries;
  std::vector<RefusedPlugin> refused;
};

namespace {

// What the host table's context points at while one file's entry runs.
struct Registration {
  const std::vector<LoadedDescriptor>* existing = nullptr;
  std::string file;
  std::vector<const tacta_descriptor*> pending;  // committed only if the whole file is accepted
  std::string error;                             // first refusal reason, empty if none
};

bool same_name(const tacta_descriptor* a, const tacta_descriptor* b) {
  return a->kind == b->kind && std::string_view(a->name) == b->name;
}

tacta_status on_register(void* context, const tacta_descriptor* descriptor) {
  auto& reg = *static_cast<Registration*>(context);
  if (!reg.error.empty()) return TACTA_ERR_INVALID_ARGUMENT;
  if (auto bad = plugin::check_descriptor(descriptor, TACTA_ABI_ID)) {
    reg.error = *bad;
    return TACTA_ERR_INVALID_ARGUMENT;
  }
  for (const tacta_descriptor* p : reg.pending) {
    if (p == descriptor) return TACTA_OK;  // the same descriptor twice is harmless
    if (same_name(p, descriptor)) {
      reg.error = std::string("registers two different ") + tacta_kind_name(descriptor->kind) +
                  " descriptors named '" + descriptor->name + "'";
      return TACTA_ERR_DUPLICATE;
    }
  }
  for (const LoadedDescriptor& e : *reg.existing) {
    if (e.descriptor == descriptor) return TACTA_OK;  // same library reached through another path
    if (same_name(e.descriptor, descriptor)) {
      reg.error = std::string(tacta_kind_name(descriptor->kind)) + " '" + descriptor->name +
                  "' is registered already by " + e.file + " (two plugins with one name)";
      return TACTA_ERR_DUPLICATE;
    }
  }
  reg.pending.push_back(descriptor);
  return TACTA_OK;
}

void on_log(void* context, int32_t level, const char* message) {
  const auto& reg = *static_cast<const Registration*>(context);
  const LogLevel levels[] = {LogLevel::debug, LogLevel::info, LogLevel::warning, LogLevel::error};
  log(levels[std::clamp(level, TACTA_LOG_DEBUG, TACTA_LOG_ERROR)],
      reg.file + ": " + (message ? message : ""));
}

std::string canonical_or_same(const std::string& path) {
  std::error_code ec;
  const fs::path p = fs::canonical(path, ec);
  return ec ? path : p.string();
}

// <prefix>/lib/tacta/plugins next to the running executable (<prefix>/bin/tacta), so a
// relocated install still finds its plugins.
std::string plugin_dir_beside_executable() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  return (exe.parent_path().parent_path() / "lib" / "tacta" / "plugins").string();
}

}  // namespace

PluginRegistry::PluginRegistry(DefaultPaths defaults) : state_(std::make_unique<State>()) {
  state_->defaults = defaults;
}

PluginRegistry::~PluginRegistry() {
  for (auto it = state_->handles.rbegin(); it != state_->handles.rend(); ++it) dlclose(*it);
}

void PluginRegistry::add_path(const std::string& directory) {
  std::error_code ec;
  if (!fs::is_directory(directory, ec))
    throw InputError({directory, 0, 0, ""},
                     "plugin path is not a folder (from --path or add_path)");
  state_->added_paths.push_back(directory);
}

void PluginRegistry::add_first_path(const std::string& directory) {
  state_->first_paths.push_back(directory);
}

std::vector<std::string> PluginRegistry::search_paths() const {
  std::vector<std::string> paths = state_->first_paths;
  if (state_->defaults == DefaultPaths::Search) {
#ifdef TACTA_BUILD_PLUGIN_DIR
    paths.emplace_back(TACTA_BUILD_PLUGIN_DIR);
#endif
    if (std::string beside = plugin_dir_beside_executable(); !beside.empty())
      paths.push_back(beside);
#ifdef TACTA_INSTALL_PLUGIN_DIR
    paths.emplace_back(TACTA_INSTALL_PLUGIN_DIR);
#endif
    if (const char* env = std::getenv("TACTA_PLUGIN_PATH")) {
      std::string_view rest(env);
      while (!rest.empty()) {
        const size_t colon = rest.find(':');
        const std::string_view part = rest.substr(0, colon);
        if (!part.empty()) paths.emplace_back(part);
        rest = colon == std::string_view::npos ? std::string_view() : rest.substr(colon + 1);
      }
    }
  }
  paths.insert(paths.end(), state_->added_paths.begin(), state_->added_paths.end());
  // Drop repeats (the build tree may be the folder beside the executable, etc.), keep order.
  std::vector<std::string> unique;
  std::set<std::string> seen;
  for (const std::string& p : paths)
    if (seen.insert(canonical_or_same(p)).second) unique.push_back(p);
  return unique;
}

void PluginRegistry::load() {
  for (const std::string& dir : search_paths()) {
    std::error_code ec;
    if (fs::is_directory(dir, ec)) load_directory(dir);
  }
}

void PluginRegistry::load_directory(const std::string& directory) {
  std::error_code ec;
  std::vector<std::string> files;
  for (const auto& item : fs::directory_iterator(directory, ec))
    if (item.path().extension() == ".so" && !item.is_directory(ec))
      files.push_back(item.path().string());
  if (ec) {
    state_->refused.push_back({directory, "cannot list folder: " + ec.message()});
    return;
  }
  std::sort(files.begin(), files.end());
  for (const std::string& file : files) load_file(file);
}

void PluginRegistry::load_file(const std::string& path) {
  const std::string file = canonical_or_same(path);
  if (!state_->seen_files.insert(file).second) return;  // reached twice through two search paths
  auto refuse = [&](std::string reason) { state_->refused.push_back({file, std::move(reason)}); };

  dlerror();
  void* handle = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    return refuse(std::string("dlopen failed: ") + (why ? why : "unknown error"));
  }
  const auto entry =
      reinterpret_cast<tacta_plugin_entry_fn>(dlsym(handle, TACTA_PLUGIN_ENTRY_SYMBOL));
  if (entry == nullptr) {
    dlclose(handle);
    return refuse("no exported function " TACTA_PLUGIN_ENTRY_SYMBOL
                  " (not a Tacta plugin, or built without TACTA_PLUGIN_EXPORT)");
  }

  Registration reg;
  reg.existing = &state_->entries;
  reg.file = file;
  const tacta_host host{sizeof(tacta_host), &reg, &on_register, &on_log};
  char message[1024] = {0};
  const tacta_status status = entry(TACTA_ABI_ID, &host, message, sizeof message);
  message[sizeof message - 1] = '\0';
  std::string reason;
  if (!reg.error.empty())
    reason = reg.error;  // the host's own reason is the precise one
  else if (status == TACTA_ERR_ABI)
    reason = std::string("ABI refused by the plugin: ") + message;
  else if (status != TACTA_OK)
    reason = "entry returned status " + std::to_string(status) + ": " + message;
  else if (reg.pending.empty())
    reason = "registered no descriptor";
  if (!reason.empty()) {
    dlclose(handle);
    return refuse(std::move(reason));
  }
  state_->handles.push_back(handle);
  for (const tacta_descriptor* d : reg.pending) state_->entries.push_back({d, file});
}

std::vector<LoadedDescriptor> PluginRegistry::list() const {
  std::vector<LoadedDescriptor> sorted = state_->entries;
  std::sort(sorted.begin(), sorted.end(), [](const LoadedDescriptor& a, const LoadedDescriptor& b) {
    if (a.descriptor->kind != b.descriptor->kind) return a.descriptor->kind < b.descriptor->kind;
    return std::string_view(a.descriptor->name) < b.descriptor->name;
  });
  return sorted;
}

const std::vector<RefusedPlugin>& PluginRegistry::refused() const { return state_->refused; }

const LoadedDescriptor* PluginRegistry::find(tacta_kind kind, std::string_view name) const {
  for (const LoadedDescriptor& e : state_->entries)
    if (e.descriptor->kind == kind && name == e.descriptor->name) return &e;
  return nullptr;
}

const LoadedDescriptor& PluginRegistry::require(tacta_kind kind, std::string_view name) const {
  if (const LoadedDescriptor* e = find(kind, name)) return *e;
  throw InputError({}, unknown_name_message(kind, name));
}

std::optional<std::span<const tacta_param_spec>> PluginRegistry::schema(
    tacta_kind kind, std::string_view name) const {
  const LoadedDescriptor* e = find(kind, name);
  if (e == nullptr) return std::nullopt;
  return std::span<const tacta_param_spec>(e->descriptor->params, e->descriptor->param_count);
}

std::string PluginRegistry::unknown_name_message(tacta_kind kind, std::string_view name) const {
  std::vector<std::string> names;
  for (const LoadedDescriptor& e : list())
    if (e.descriptor->kind == kind) names.emplace_back(e.descriptor->name);
  const std::string kind_name = tacta_kind_name(kind);
  std::string text = "no " + kind_name + " plugin named '" + std::string(name) + "'";
  if (names.empty()) {
    text += "; no " + kind_name + " plugins are loaded (searched:";
    for (const std::string& p : search_paths()) text += " " + p;
    return text + "; see `tacta plugins`)";
  }
  if (const auto close = closest_names(name, names); !close.empty())
    text += "; did you mean '" + close.front() + "'?";
  text += " available " + kind_name + " plugins:";
  for (size_t i = 0; i < names.size(); ++i) text += (i ? ", " : " ") + names[i];
  return text;
}

}  // namespace tacta
