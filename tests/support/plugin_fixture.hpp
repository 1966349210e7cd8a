// Test support: loads one plugin shared library through the real C ABI (dlopen + entry point),
// without the engine's loader, so plugin tests exercise exactly what a host sees.
#pragma once

#include <dlfcn.h>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "tacta/param_defaults.hpp"
#include "tacta/plugin.h"

namespace tacta::testing {

class LoadedPlugin {
 public:
  // file: a name under the build tree's plugin folder ("tacta_tensor_mass.so") or a full path.
  explicit LoadedPlugin(const std::string& file) {
    const std::string path =
        file.find('/') == std::string::npos ? std::string(TACTA_PLUGIN_DIR) + "/" + file : file;
    handle_ = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle_ == nullptr) throw std::runtime_error(std::string("dlopen: ") + dlerror());
    auto entry = reinterpret_cast<tacta_plugin_entry_fn>(dlsym(handle_, TACTA_PLUGIN_ENTRY_SYMBOL));
    if (entry == nullptr) throw std::runtime_error(path + ": no tacta_plugin_entry");
    tacta_host host{sizeof(tacta_host), this, &LoadedPlugin::on_register, nullptr};
    char message[512] = {0};
    if (entry(TACTA_ABI_ID, &host, message, sizeof message) != TACTA_OK)
      throw std::runtime_error(path + ": entry refused: " + message);
  }
  ~LoadedPlugin() {
    if (handle_ != nullptr) dlclose(handle_);
  }
  LoadedPlugin(const LoadedPlugin&) = delete;
  LoadedPlugin& operator=(const LoadedPlugin&) = delete;

  const std::vector<const tacta_descriptor*>& descriptors() const { return descriptors_; }

  const tacta_descriptor& descriptor(const std::string& name) const {
    for (const tacta_descriptor* d : descriptors_)
      if (name == d->name) return *d;
    throw std::runtime_error("no descriptor named " + name);
  }
  template <class Api>
  const Api& api(const std::string& name) const {
    return *static_cast<const Api*>(descriptor(name).api);
  }

 private:
  static tacta_status on_register(void* context, const tacta_descriptor* d) {
    static_cast<LoadedPlugin*>(context)->descriptors_.push_back(d);
    return TACTA_OK;
  }
  void* handle_ = nullptr;
  std::vector<const tacta_descriptor*> descriptors_;
};

// Default parameter values from a schema (tacta::defaults_of), as the engine passes them when a
// scene sets none, as a vector a test may edit in place. The C views point into a shared ParamSet,
// so copies and moves of this value stay valid; keep it as DefaultParams (or auto), not as a plain
// std::vector, or the CHOICE names and VECTOR values it points to go away with it.
struct DefaultParams : std::vector<tacta_param_value> {
  std::shared_ptr<const ParamSet> storage;
};
inline DefaultParams default_params(const tacta_descriptor& d) {
  DefaultParams values;
  values.storage = std::make_shared<const ParamSet>(defaults_of(d));
  values.assign(values.storage->data(), values.storage->data() + values.storage->size());
  return values;
}

}  // namespace tacta::testing
