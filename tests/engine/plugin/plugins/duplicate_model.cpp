// Test plugin: compiled into two files that both register the model "test_duplicate".
#include <array>

#include "tacta/sdk/model.hpp"

namespace {

class Duplicate {
 public:
  static constexpr const char* kName = "test_duplicate";
  static constexpr const char* kDescription = "registered by two files (test only)";
  static constexpr uint32_t kVersion = 1;
  static constexpr std::array<tacta_param_spec, 0> kParams{};
  explicit Duplicate(const tacta_model_setup&) {}
  uint32_t step(tacta_body_state&, double) noexcept { return TACTA_STEP_OK; }
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<Duplicate>())
