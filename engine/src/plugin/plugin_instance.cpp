#include "plugin/plugin_instance.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>

namespace tacta {

namespace {
constexpr size_t kMessageCapacity = 1024;

std::string plugin_failure(const tacta_descriptor& d, const char* what, const char* message) {
  std::string text = std::string(tacta_kind_name(d.kind)) + " plugin '" + d.name + "' " + what;
  if (message[0] != '\0') text += ": " + std::string(message);
  return text;
}

// A plugin's save_state (model or device): the size asked first, then the bytes; a plugin whose
// state grew between the two calls is asked again.
template <class Save>
std::vector<uint8_t> saved_state(Save&& save) {
  std::vector<uint8_t> bytes(save(nullptr, 0));
  while (true) {
    const size_t size = save(bytes.data(), bytes.size());
    if (size <= bytes.size()) {
      bytes.resize(size);
      return bytes;
    }
    bytes.resize(size);
  }
}

// A plugin's load_state answer: true, or false with the plugin's reason in `why`.
bool state_loaded(const tacta_descriptor& d, tacta_status status, const char* message,
                  std::string& why) {
  if (status == TACTA_OK) return true;
  why = plugin_failure(d, "refused its state", message);
  return false;
}
}  // namespace

ModelInstance::ModelInstance(const tacta_descriptor& descriptor, const tacta_model_setup& given,
                             const SourceLocation& where, JobPool* jobs)
    : descriptor_(descriptor), api_(*static_cast<const tacta_model_api*>(descriptor.api)) {
  services_ = host_services(jobs, &arena_);
  tacta_model_setup setup = given;
  setup.struct_size = sizeof setup;
  setup.host = &services_;
  char message[kMessageCapacity] = {0};
  if (api_.create(&setup, &instance_, message, sizeof message) != TACTA_OK || instance_ == nullptr)
    throw InputError(where, plugin_failure(descriptor, "refused this body", message));
}

ModelInstance::~ModelInstance() {
  if (instance_ != nullptr) api_.destroy(instance_);
}

bool ModelInstance::can_save_state(std::string& why) const {
  if (tacta_model_has_state_entries(&api_, descriptor_.api_size) ||
      (tacta_model_claims(&api_, descriptor_.api_size) & TACTA_MODEL_CLAIM_NO_HISTORY) != 0)
    return true;
  why = "model '" + std::string(descriptor_.name) +
        "' has no save_state/load_state entries and does not claim TACTA_MODEL_CLAIM_NO_HISTORY";
  return false;
}

std::vector<uint8_t> ModelInstance::save_state() {
  if (!tacta_model_has_state_entries(&api_, descriptor_.api_size)) return {};
  return saved_state(
      [this](void* bytes, size_t capacity) { return api_.save_state(instance_, bytes, capacity); });
}

bool ModelInstance::load_state(std::span<const uint8_t> bytes, std::string& why) {
  if (!tacta_model_has_state_entries(&api_, descriptor_.api_size)) {
    if (bytes.empty()) return true;
    why = "model '" + std::string(descriptor_.name) + "' has no load_state for " +
          std::to_string(bytes.size()) + " bytes of state";
    return false;
  }
  char message[kMessageCapacity] = {};
  return state_loaded(
      descriptor_, api_.load_state(instance_, bytes.data(), bytes.size(), message, sizeof message),
      message, why);
}

std::vector<std::pair<std::string, double>> ModelInstance::counters() {
  std::vector<std::pair<std::string, double>> named;
  // An entry past the plugin's own table size is absent (a plugin built before it existed).
  if (descriptor_.api_size < offsetof(tacta_model_api, counters) + sizeof(api_.counters) ||
      api_.counters == nullptr)
    return named;
  std::vector<tacta_model_counter> raw(api_.counters(instance_, nullptr, 0));
  raw.resize(std::min<size_t>(
      raw.size(), api_.counters(instance_, raw.data(), static_cast<uint32_t>(raw.size()))));
  for (const tacta_model_counter& c : raw)
    if (c.name != nullptr) named.emplace_back(c.name, c.value);
  return named;
}

DeviceInstance::DeviceInstance(const tacta_descriptor& descriptor, const tacta_device_setup& setup,
                               const SourceLocation& where)
    : descriptor_(descriptor), api_(*static_cast<const tacta_device_api*>(descriptor.api)) {
  char message[kMessageCapacity] = {0};
  if (api_.create(&setup, &instance_, message, sizeof message) != TACTA_OK || instance_ == nullptr)
    throw InputError(where, plugin_failure(descriptor, "could not be created", message));
  api_.capabilities(instance_, &capabilities_);
}

DeviceInstance::~DeviceInstance() {
  if (instance_ == nullptr) return;
  if (connected_) api_.disconnect(instance_);
  api_.destroy(instance_);
}

bool DeviceInstance::has_entry(size_t offset, const void* entry) const noexcept {
  // An entry past the plugin's own table size is absent (a plugin built before it existed).
  return descriptor_.api_size >= offset + sizeof(void*) && entry != nullptr;
}

bool DeviceInstance::has_state() const noexcept {
  return tacta_device_has_state_entries(&api_, descriptor_.api_size) != 0;
}

std::vector<uint8_t> DeviceInstance::save_state() {
  if (!has_state()) return {};
  return saved_state(
      [this](void* bytes, size_t capacity) { return api_.save_state(instance_, bytes, capacity); });
}

bool DeviceInstance::load_state(std::span<const uint8_t> bytes, std::string& why) {
  if (!has_state()) return true;  // a live link: it reconnects
  char message[kMessageCapacity] = {};
  return state_loaded(
      descriptor_, api_.load_state(instance_, bytes.data(), bytes.size(), message, sizeof message),
      message, why);
}

bool DeviceInstance::input(const double* values, uint32_t count) noexcept {
  if (!has_entry(offsetof(tacta_device_api, input), reinterpret_cast<const void*>(api_.input)))
    return false;
  api_.input(instance_, values, count);
  return true;
}

bool DeviceInstance::wants_surface() const noexcept {
  return has_entry(offsetof(tacta_device_api, surface),
                   reinterpret_cast<const void*>(api_.surface));
}

void DeviceInstance::surface(const tacta_device_surface& surface) noexcept {
  if (wants_surface()) api_.surface(instance_, &surface);
}

std::vector<std::pair<std::string, double>> DeviceInstance::counters() {
  std::vector<std::pair<std::string, double>> out;
  if (!has_entry(offsetof(tacta_device_api, counters),
                 reinterpret_cast<const void*>(api_.counters)))
    return out;
  std::vector<tacta_device_counter> buffer(64);
  const uint32_t n = std::min<uint32_t>(api_.counters(instance_, buffer.data(), 64), 64);
  for (uint32_t i = 0; i < n; ++i)
    if (buffer[i].name != nullptr) out.emplace_back(buffer[i].name, buffer[i].value);
  return out;
}

void DeviceInstance::connect(const SourceLocation& where) {
  char message[kMessageCapacity] = {0};
  if (api_.connect(instance_, message, sizeof message) != TACTA_OK)
    throw InputError(where, plugin_failure(descriptor_, "could not connect", message));
  connected_ = true;
  // A bridged device announces its capabilities when it connects (plugins/devices/net).
  api_.capabilities(instance_, &capabilities_);
}

tacta_device_state DeviceInstance::status(char* reason, size_t capacity) noexcept {
  if (capacity > 0) reason[0] = '\0';
  if (api_.status != nullptr) return api_.status(instance_, reason, capacity);
  return connected_ ? TACTA_DEVICE_CONNECTED : TACTA_DEVICE_DISCONNECTED;
}

}  // namespace tacta
