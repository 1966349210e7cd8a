// Test support for device plugins: parameters by name on top of the schema defaults, and an
// instance created, connected and destroyed through the real C function table.
#pragma once

#include <gtest/gtest.h>
#include <string>
#include <vector>

#include "plugin_fixture.hpp"
#include "tacta/device_api.h"

namespace tacta::testing {

class DeviceParams {
 public:
  explicit DeviceParams(const tacta_descriptor& d)
      : descriptor_(d), values_(default_params(d)), vectors_(d.param_count), texts_(d.param_count) {
    for (uint32_t i = 0; i < d.param_count; ++i)
      if (values_[i].values != nullptr)
        vectors_[i].assign(values_[i].values, values_[i].values + values_[i].count);
  }
  DeviceParams& number(const std::string& name, double v) {
    values_[index(name)].number = v;
    return *this;
  }
  DeviceParams& vector(const std::string& name, std::vector<double> v) {
    vectors_[index(name)] = std::move(v);
    return *this;
  }
  DeviceParams& text(const std::string& name, std::string v) {
    const uint32_t i = index(name);
    texts_[i] = std::move(v);
    values_[i].text = nullptr;  // bound in setup()
    return *this;
  }
  tacta_device_setup setup(uint64_t seed = 1, const std::string& base_directory = "") {
    base_directory_ = base_directory;
    for (uint32_t i = 0; i < descriptor_.param_count; ++i) {
      if (descriptor_.params[i].type == TACTA_PARAM_VECTOR) {
        values_[i].values = vectors_[i].data();
        values_[i].count = static_cast<uint32_t>(vectors_[i].size());
      }
      if (descriptor_.params[i].type == TACTA_PARAM_TEXT && !texts_[i].empty())
        values_[i].text = texts_[i].c_str();
    }
    return {sizeof(tacta_device_setup), values_.data(), static_cast<uint32_t>(values_.size()),
            base_directory_.c_str(),    seed,           1e-3};
  }

 private:
  uint32_t index(const std::string& name) const {
    for (uint32_t i = 0; i < descriptor_.param_count; ++i)
      if (name == descriptor_.params[i].name) return i;
    throw std::runtime_error("no parameter " + name);
  }
  const tacta_descriptor& descriptor_;
  DefaultParams values_;
  std::vector<std::vector<double>> vectors_;
  std::vector<std::string> texts_;
  std::string base_directory_;
};

// One device instance through the C ABI. create_status()/message() tell why create failed.
class DeviceInstance {
 public:
  DeviceInstance(const tacta_device_api& api, const tacta_device_setup& setup) : api_(api) {
    status_ = api_.create(&setup, &instance_, message_, sizeof message_);
    if (status_ == TACTA_OK) status_ = api_.connect(instance_, message_, sizeof message_);
  }
  ~DeviceInstance() {
    if (instance_ != nullptr) api_.destroy(instance_);
  }
  DeviceInstance(const DeviceInstance&) = delete;
  DeviceInstance& operator=(const DeviceInstance&) = delete;

  tacta_status create_status() const { return status_; }
  std::string message() const { return message_; }
  tacta_device_state read(double time, tacta_device_sample& s) {
    return api_.read(instance_, time, &s);
  }
  tacta_device_sample read(double time) {
    tacta_device_sample s{};
    api_.read(instance_, time, &s);
    return s;
  }
  void write(double time, double fx, double fy, double fz) {
    tacta_device_command c{{fx, fy, fz}, {0.0, 0.0, 0.0}};
    api_.write(instance_, time, &c);
  }
  tacta_device_capabilities capabilities() {
    tacta_device_capabilities c{};
    api_.capabilities(instance_, &c);
    return c;
  }
  tacta_device_state status(std::string& reason) {
    char buffer[512] = {0};
    const tacta_device_state s = api_.status(instance_, buffer, sizeof buffer);
    reason = buffer;
    return s;
  }
  void disconnect() { api_.disconnect(instance_); }

 private:
  const tacta_device_api& api_;
  void* instance_ = nullptr;
  tacta_status status_ = TACTA_ERR_INTERNAL;
  char message_[1024] = {0};
};

}  // namespace tacta::testing
