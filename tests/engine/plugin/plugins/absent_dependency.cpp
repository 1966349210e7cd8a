// Test plugin: linked against libtacta_test_absent_dep.so, which the loader cannot find at run
// time (the plugin carries no RPATH to it), so dlopen fails and must name that library.
#include <array>

#include "tacta/sdk/model.hpp"

// Default visibility: the definition lives in another shared library.
TACTA_EXPORT int tacta_test_absent_dep_value();  // defined in absent_dep_lib.cpp

namespace {

class NeedsLibrary {
 public:
  static constexpr const char* kName = "test_needs_library";
  static constexpr const char* kDescription = "depends on a missing library (test only)";
  static constexpr uint32_t kVersion = 1;
  static constexpr std::array<tacta_param_spec, 0> kParams{};
  explicit NeedsLibrary(const tacta_model_setup&) {}
  uint32_t step(tacta_body_state&, double) noexcept {
    return static_cast<uint32_t>(tacta_test_absent_dep_value()) & 0u;
  }
};

}  // namespace

TACTA_PLUGIN_EXPORT(tacta::sdk::model_descriptor<NeedsLibrary>())
