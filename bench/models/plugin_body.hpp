// One body driven through a model plugin's C ABI, as the engine drives it: the plugin is loaded
// with dlopen (tests/support/plugin_fixture.hpp), created with its schema defaults plus named
// overrides, and stepped on engine-owned arrays. Used to time every model the same way.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "plugin_fixture.hpp"
#include "tacta/model_api.h"
#include "tacta/models/test_meshes.hpp"

namespace tacta::bench {

struct ParamOverride {
  std::string name;
  double number;     // REAL, INT, BOOL, or the CHOICE index
  const char* text;  // CHOICE name, else nullptr
};

inline bool plugin_built(const std::string& file) {
  return std::filesystem::exists(std::string(TACTA_PLUGIN_DIR) + "/" + file);
}

class PluginBody {
 public:
  PluginBody(const std::string& file, const std::string& model, const models::TestMesh& mesh,
             const tacta_material& material, std::array<double, 3> gravity, double dt,
             const std::vector<ParamOverride>& overrides,
             const tacta_host_services* host = nullptr)
      : plugin_(std::make_unique<testing::LoadedPlugin>(file)),
        api_(plugin_->api<tacta_model_api>(model)),
        mesh_(mesh),
        view_(mesh_.view()),
        material_(material),
        positions_(mesh_.positions),
        velocities_(positions_.size(), 0.0),
        forces_(positions_.size(), 0.0),
        dt_(dt) {
    const tacta_descriptor& d = plugin_->descriptor(model);
    params_ = testing::default_params(d);
    for (const ParamOverride& o : overrides) {
      bool found = false;
      for (uint32_t i = 0; i < d.param_count; ++i)
        if (o.name == d.params[i].name) {
          params_[i].number = o.number;
          if (o.text) params_[i].text = o.text;
          found = true;
        }
      if (!found) throw std::runtime_error(model + " has no parameter " + o.name);
    }
    for (uint32_t i = 0; i < mesh_.node_count(); ++i)
      for (int c = 0; c < 3; ++c) forces_[3 * i + c] = mesh_.masses[i] * gravity[c];
    const tacta_model_setup setup{sizeof(tacta_model_setup),
                                  &view_,
                                  &material_,
                                  mesh_.masses.data(),
                                  mesh_.fixed.data(),
                                  params_.data(),
                                  d.param_count,
                                  dt,
                                  host};
    char message[512] = {0};
    if (api_.create(&setup, &instance_, message, sizeof message) != TACTA_OK)
      throw std::runtime_error(model + ": create failed: " + message);
    state_ = {mesh_.node_count(), positions_.data(), velocities_.data(), forces_.data(), 0.0};
    if (api_.begin) api_.begin(instance_, &state_, dt_);
  }
  ~PluginBody() {
    if (instance_) api_.destroy(instance_);
  }
  PluginBody(const PluginBody&) = delete;
  PluginBody& operator=(const PluginBody&) = delete;

  uint32_t step() {
    const uint32_t bits = api_.step(instance_, &state_, dt_);
    state_.time += dt_;
    return bits;
  }
  const std::vector<double>& positions() const { return positions_; }

 private:
  std::unique_ptr<testing::LoadedPlugin> plugin_;
  const tacta_model_api& api_;
  models::TestMesh mesh_;
  tacta_mesh_view view_;
  tacta_material material_;
  testing::DefaultParams params_;
  std::vector<double> positions_, velocities_, forces_;
  tacta_body_state state_{};
  void* instance_ = nullptr;
  double dt_;
};

}  // namespace tacta::bench
