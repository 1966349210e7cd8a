// RAII owners of plugin instances (a model for a body, a device for the haptic loop). create()
// runs at load time and may throw InputError with the plugin's own message; the per-tick calls
// are thin, noexcept forwards into the C function table.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "../services/job_pool.hpp"
#include "tacta/device_api.h"
#include "tacta/error.hpp"
#include "tacta/model_api.h"
#include "tacta/param_set.hpp"
#include "tacta/scene.hpp"

namespace tacta {

class ModelInstance {
 public:
  // Throws InputError (at `where`) when the plugin refuses the setup. The instance gets the host
  // services (parallel_for on `jobs`, serial when null; a scratch arena of its own).
  ModelInstance(const tacta_descriptor& descriptor, const tacta_model_setup& setup,
                const SourceLocation& where, JobPool* jobs = nullptr);
  ~ModelInstance();
  ModelInstance(const ModelInstance&) = delete;
  ModelInstance& operator=(const ModelInstance&) = delete;

  const char* name() const noexcept { return descriptor_.name; }
  const tacta_descriptor& descriptor() const noexcept { return descriptor_; }
  uint32_t claims() const noexcept {
    return tacta_model_claims(&api_, static_cast<uint32_t>(descriptor_.api_size));
  }
  // The completed parameters the instance was built with (World::make_model sets them), so a
  // rebuild on another mesh (a cut) makes the same model.
  const ParamSet& params() const noexcept { return params_; }
  void set_params(ParamSet params) { params_ = std::move(params); }
  uint32_t step(tacta_body_state& state, double dt) noexcept {
    return api_.step(instance_, &state, dt);
  }
  void begin(const tacta_body_state& state, double dt) noexcept {
    if (api_.begin) api_.begin(instance_, &state, dt);
  }
  double elastic_energy(const double* positions) noexcept {
    return api_.elastic_energy ? api_.elastic_energy(instance_, positions) : 0.0;
  }
  bool has_internal_forces() const noexcept { return api_.internal_forces != nullptr; }
  // Elastic forces at these positions (3 per node, N); false when the model has no such entry.
  bool internal_forces(const double* positions, double* forces) noexcept {
    if (!api_.internal_forces) return false;
    api_.internal_forces(instance_, positions, forces);
    return true;
  }
  bool has_stress() const noexcept { return api_.node_stress != nullptr; }
  void node_stress(const double* positions, double* von_mises) noexcept {
    if (api_.node_stress) api_.node_stress(instance_, positions, von_mises);
  }

  // Changes parameter `index` while the model is not stepping (the optional set_param entry);
  // false with the plugin's reason in `why` when it has no such entry or refuses the change.
  bool set_param(uint32_t index, const tacta_param_value& value, std::string& why) {
    if (!api_.set_param) {
      why = "the model has no set_param entry";
      return false;
    }
    char message[256] = {};
    if (api_.set_param(instance_, index, &value, message, sizeof message) == TACTA_OK) return true;
    why = message;
    return false;
  }

  // The model's own counters (solver fallbacks, Newton iterations); empty when it keeps none.
  // Allocates: not from the 1 kHz path.
  std::vector<std::pair<std::string, double>> counters();
  // What the instance says it chose for this body (empty when the plugin says nothing).
  std::string describe() const {
    // A plugin built before `describe` existed has a shorter table: the entry is absent.
    if (descriptor_.api_size < offsetof(tacta_model_api, describe) + sizeof(api_.describe) ||
        !api_.describe)
      return {};
    char text[512] = {};
    api_.describe(instance_, text, sizeof text);
    return text;
  }

  // Checkpoints (model_api.h save_state / load_state, or the NO_HISTORY claim). Not from the
  // 1 kHz path. can_save: false with why (naming the model) when neither is there.
  bool can_save_state(std::string& why) const;
  std::vector<uint8_t> save_state();  // empty for a model that claims no history
  // Sets the instance's own state from what save_state wrote; false with the model's reason.
  bool load_state(std::span<const uint8_t> bytes, std::string& why);

  // Link for the retired-instance stack of a runtime swap (see ModelMailbox).
  ModelInstance* retired_next = nullptr;
  size_t scratch_bytes() const noexcept { return arena_.bytes(); }  // host scratch granted

 private:
  const tacta_descriptor& descriptor_;
  const tacta_model_api& api_;
  ParamSet params_;
  ScratchArena arena_;  // outlives the instance: freed after destroy()
  tacta_host_services services_{};
  void* instance_ = nullptr;
};

class DeviceInstance {
 public:
  DeviceInstance(const tacta_descriptor& descriptor, const tacta_device_setup& setup,
                 const SourceLocation& where);
  ~DeviceInstance();
  DeviceInstance(const DeviceInstance&) = delete;
  DeviceInstance& operator=(const DeviceInstance&) = delete;

  const char* name() const noexcept { return descriptor_.name; }
  // Connects; throws InputError with the device's reason when it cannot.
  void connect(const SourceLocation& where);
  tacta_device_state read(double time, tacta_device_sample& sample) noexcept {
    return api_.read(instance_, time, &sample);
  }
  void write(double time, const tacta_device_command& command) noexcept {
    api_.write(instance_, time, &command);
  }
  const tacta_device_capabilities& capabilities() const noexcept { return capabilities_; }
  // Host input (the optional `input` entry); false when the plugin has none. Any host thread.
  bool input(const double* values, uint32_t count) noexcept;
  // The device's own account of its state; fills reason (NUL-terminated) when not connected.
  tacta_device_state status(char* reason, size_t capacity) noexcept;
  // Whether the plugin takes a body surface (the optional `surface` entry), and hands it one.
  bool wants_surface() const noexcept;
  void surface(const tacta_device_surface& surface) noexcept;
  // Checkpoints (device_api.h save_state / load_state): false when the plugin has none (a live
  // link, which reconnects instead). load_state: false with the plugin's reason.
  bool has_state() const noexcept;
  std::vector<uint8_t> save_state();
  bool load_state(std::span<const uint8_t> bytes, std::string& why);
  // The plugin's counters for report.json (the optional `counters` entry); empty without it.
  std::vector<std::pair<std::string, double>> counters();

 private:
  // The optional entry at `offset` when the plugin's table reaches it and it is set.
  bool has_entry(size_t offset, const void* entry) const noexcept;
  const tacta_descriptor& descriptor_;
  const tacta_device_api& api_;
  void* instance_ = nullptr;
  bool connected_ = false;
  tacta_device_capabilities capabilities_{};
};

}  // namespace tacta
