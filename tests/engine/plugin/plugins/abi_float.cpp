// Test plugin: built with -DTACTA_SCALAR_FLOAT, so its ABI id has the scalar bit clear and the
// SDK entry refuses a double host, naming that bit.
#include <array>

#include "tacta/sdk/model.hpp"

#ifndef TACTA_SCALAR_FLOAT
#error "this test plugin must be built with TACTA_SCALAR_FLOAT"
#endif

namespace {

class FloatModel {
 public:
  static constexpr const char* kName = "test_float_model";
  static constexpr const char* kDescription = "built for float state (test only)";
  static constexpr uint32_t kVersion = 1;
  static constexpr std::array<tacta_param_spec, 0> kParams{};
  explicit FloatModel(const tacta_model_setup&) {}
  uint32_t step(tacta_body_state&, double) noexcept { return TACTA_STEP_OK; }
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<FloatModel>())
