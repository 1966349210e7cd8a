// Test plugin: a collision response built as if against the header before collision roles
// existed. Its function table ends before `roles` (api_size says so), so the engine must guess
// its roles from its entries: respond only, hence the response role. It counts its calls
// (tacta_test_legacy_response_calls) so a test can see the engine picked it.
#include <array>
#include <atomic>
#include <cstddef>

#include "tacta/sdk/collision.hpp"

namespace {

std::atomic<long> respond_calls{0};

class LegacyResponse {
 public:
  static constexpr const char* kName = "test_legacy_response";
  static constexpr const char* kDescription =
      "a response that moves nothing, without declared roles (test only)";
  static constexpr uint32_t kVersion = 10000;
  static constexpr std::array<tacta_param_spec, 0> kParams{};
  explicit LegacyResponse(const tacta_collision_setup&) {}
  uint32_t respond(tacta_collision_world&, tacta_contact*, uint32_t) noexcept {
    ++respond_calls;
    return TACTA_COLLIDE_OK;
  }
};

const tacta_descriptor* legacy_descriptor() {
  static tacta_descriptor d = *tacta::sdk::collision_descriptor<LegacyResponse>();
  d.api_size = offsetof(tacta_collision_api, roles);  // the old table's size
  return &d;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) long tacta_test_legacy_response_calls() {
  return respond_calls;
}

TACTA_PLUGIN_EXPORT(legacy_descriptor())
